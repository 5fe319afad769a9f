// Bad scans give a clear error or a warning, never a made-up number: empty, blank, two marks, border, wrong shape.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/render/render.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::vision {
namespace {

// A 1200 dpi scan of paper (0.88, 1 % noise) with dark strokes along the given polylines (px).
cv::Mat paper_with(const std::vector<std::vector<Point2>>& strokes, double radius_px = 4.7, cv::Size size = {1200, 300}) {
  cv::Mat coverage = cv::Mat::zeros(size, CV_32F);
  for (const auto& s : strokes) draw_stroke_coverage(coverage, s, radius_px);
  cv::Mat noise(size, CV_32F);
  cv::RNG rng(3);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 0.01);
  cv::Mat value = 0.88 * (1.0 - 0.75 * coverage) + noise;
  cv::Mat out;
  value.convertTo(out, CV_8U, 255.0);
  return out;
}

std::string error_of(const cv::Mat& image, int sides = 1) {
  ScanOptions o;
  o.sides = sides;
  o.label = "scan.png";
  try {
    analyse_scan(image, 1200, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

void expect_error(const std::string& what, const std::string& part) {
  EXPECT_NE(what.find(part), std::string::npos) << what;
  EXPECT_EQ(what.rfind("scan.png: ", 0), 0u) << what;  // names the image
}

TEST(ScanErrors, EmptyImageAndWrongPixelType) {
  expect_error(error_of(cv::Mat()), "the image is empty");
  expect_error(error_of(cv::Mat(100, 100, CV_8UC3, cv::Scalar(200, 200, 200))), "one-channel");
  expect_error(error_of(cv::Mat(100, 100, CV_32F, cv::Scalar(0.5))), "one-channel");
  expect_error(error_of(cv::Mat(5, 5, CV_8U, cv::Scalar(200))), "too small");
}

TEST(ScanErrors, BlankPaperAndOnlySpecksHaveNoMark) {
  expect_error(error_of(paper_with({})), "no mark found");
  expect_error(error_of(cv::Mat(300, 300, CV_8U, cv::Scalar(225))), "no mark found");
  // Dust specks 0.1 mm across are not a mark.
  const cv::Mat specks = paper_with({{{100, 100}}, {{400, 150}}, {{900, 60}}}, 2.5);
  expect_error(error_of(specks), "no mark found: the largest dark feature is only");
}

TEST(ScanErrors, TwoSeparateMarksOrAnInterruptedOne) {
  expect_error(error_of(paper_with({{{100, 100}, {1100, 100}}, {{100, 200}, {900, 210}}})), "found two separate marks");
  expect_error(error_of(paper_with({{{100, 150}, {600, 150}}, {{640, 150}, {1100, 150}}})), "or the mark is interrupted");
}

TEST(ScanErrors, MarkTouchingTheBorder) {
  expect_error(error_of(paper_with({{{-20, 150}, {900, 150}}})), "touches the left border");
  expect_error(error_of(paper_with({{{300, 150}, {1250, 160}}})), "touches the right border");
  RenderOptions o;
  o.margin_m = 0;
  const auto scan = render_scan(sample_shape(triangle_shape(0.01), {}), true, o);
  expect_error(error_of(scan.image, 3), "touches the");
}

TEST(ScanErrors, WrongShapeIsNotForcedIntoNumbers) {
  RenderOptions o;
  o.texture = 0;
  const auto triangle = render_scan(sample_shape(triangle_shape(0.02), {}), true, o);
  expect_error(error_of(triangle.image, 1), "is not a straight line");
  const auto line = render_scan(sample_shape(line_shape(0.03), {}), false, o);
  expect_error(error_of(line.image, 3), "straight sides");
  const auto bent = render_scan(sample_shape(PathShape{{{0, 0}, {0.02, 0}, {0.03, 0.012}}, false}, {}), false, o);
  expect_error(error_of(bent.image, 1), "is not a straight line");
  expect_error(error_of(bent.image, 3), "straight sides");
  ScanOptions two;
  two.sides = 2;
  const auto r = analyse_scan(bent.image, 1200, two);  // the right shape measures fine
  ASSERT_EQ(r.metrics.sides.size(), 2u);
  EXPECT_NEAR(r.metrics.sides[0].length_m, 0.02, 5e-6);
  EXPECT_NEAR(r.metrics.sides[1].length_m, std::hypot(0.01, 0.012), 5e-6);
  EXPECT_FALSE(r.metrics.closed);
}

TEST(ScanErrors, DefectsOnTheMarkBecomeWarnings) {
  // A blob of dust on the mark and a square (not round) end: measured, with warnings, never silently.
  cv::Mat image = paper_with({{{100, 150}, {1000, 150}}});
  cv::circle(image, cv::Point(500, 157), 4, cv::Scalar(60), -1);
  cv::rectangle(image, cv::Point(1000, 146), cv::Point(1012, 154), cv::Scalar(60), -1);
  const auto r = analyse_scan(image, 1200);
  bool square_end = false;
  for (const auto& w : r.warnings) square_end = square_end || w.find("not a round laser-spot end") != std::string::npos;
  EXPECT_TRUE(square_end);
  EXPECT_GT(r.sides[0].rejected_sections, 0u);
}

}  // namespace
}  // namespace stiffpath::vision
