// Tests of the synthetic scan renderer: exact stroke areas, ground truth, reproducibility and option checks.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <unistd.h>
#include <opencv2/imgcodecs.hpp>

#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/vision/render/render.hpp"
#include "stiffpath/vision/io/resolution.hpp"

namespace stiffpath::vision {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Render, StrokeCoverageIntegratesToTheCapsuleArea) {
  // Area of all points within r of a segment of length L: 2rL + πr², for any angle and sub-pixel phase.
  for (const double angle : {0.0, 0.0123, 0.4, 1.2}) {
    for (const double r : {1.3, 4.7}) {
      cv::Mat cov = cv::Mat::zeros(400, 400, CV_32F);
      const Point2 a{60.37, 80.81};
      const double len = 250.0;
      draw_stroke_coverage(cov, {a, a + len * Point2{std::cos(angle), std::sin(angle)}}, r);
      EXPECT_NEAR(cv::sum(cov)[0], 2 * r * len + kPi * r * r, 0.06) << "angle " << angle << " r " << r;
      double lo, hi;
      cv::minMaxLoc(cov, &lo, &hi);
      EXPECT_GE(lo, 0.0);
      EXPECT_LE(hi, 1.0);
    }
  }
  // A right-angled corner: two bands 2r wide, two end half-disks, a quarter disk outside the corner,
  // minus the r × r square where the bands overlap inside it (counted once: max, not sum).
  cv::Mat cov = cv::Mat::zeros(200, 200, CV_32F);
  const double r = 3.0;
  draw_stroke_coverage(cov, {{20.2, 20.2}, {150.2, 20.2}, {150.2, 150.2}}, r);
  EXPECT_NEAR(cv::sum(cov)[0], 2 * r * 260 + kPi * r * r + kPi * r * r / 4 - r * r, 0.06);
}

TEST(Render, GroundTruthOfLineAndTriangle) {
  RenderOptions o;
  o.rotation_rad = 0.03;
  o.texture = 0;
  const auto line = render_scan(sample_shape(line_shape(0.03), {}), false, o);
  EXPECT_NEAR(line.truth.length_m, 0.03, 1e-12);
  EXPECT_LT(line.truth.deviation_area_m2, 1e-18);
  // The image is just large enough: path extent + 2·(margin + w/2) at 1200 dpi.
  const double px_per_m = 1200 / 0.0254;
  EXPECT_NEAR(line.image.cols, (0.03 * std::cos(0.03) + 2 * (o.margin_m + o.mark_width_m / 2)) * px_per_m, 1.0);
  EXPECT_EQ(line.image.type(), CV_8U);

  const auto tri = render_scan(sample_shape(triangle_shape(0.02), {}), true, o);
  ASSERT_EQ(tri.truth.sides.size(), 3u);
  for (const auto& s : tri.truth.sides) EXPECT_NEAR(s.length_m, 0.02, 1e-12);
  // Sides listed from the bottom-left corner clockwise on screen: the first side goes up (−y) and right.
  EXPECT_LT(tri.truth.sides[0].fit.line.direction.y(), 0.0);
  EXPECT_GT(tri.truth.sides[0].fit.line.direction.x(), 0.0);
}

TEST(Render, WiggleTruthMatchesItsClosedForm) {
  // A slowly decaying wiggle on a line: area ≈ (2/π)·A·τ·(1 − e^(−L/τ)) for many periods (the TLS line
  // barely tilts), the largest offset ≈ A (within the line's small tilt and shift).
  const Wiggle w{5e-5, 5e-3, 0.2};
  RenderOptions o;
  o.texture = 0;
  o.noise = 0;
  const auto scan = render_scan(sample_shape(line_shape(0.05), w), false, o);
  const double expected = 2 / kPi * w.amplitude_m * w.decay_length_m * (1 - std::exp(-0.05 / w.decay_length_m));
  EXPECT_NEAR(scan.truth.deviation_area_m2, expected, 0.01 * expected);
  EXPECT_NEAR(scan.truth.max_deviation_m, w.amplitude_m, 0.1 * w.amplitude_m);
}

TEST(Render, SameSeedSameImageOtherSeedOther) {
  RenderOptions o;
  o.specks = 5;
  const auto sides = sample_shape(line_shape(0.01), {});
  const auto a = render_scan(sides, false, o), b = render_scan(sides, false, o);
  EXPECT_EQ(cv::norm(a.image, b.image, cv::NORM_INF), 0.0);
  o.seed = 2;
  const auto c = render_scan(sides, false, o);
  EXPECT_GT(cv::norm(a.image, c.image, cv::NORM_INF), 0.0);
}

TEST(Render, SixteenBitAndColourImagesAreProportionalToTheGreyOne) {
  RenderOptions o;
  o.noise = 0;
  const auto sides = sample_shape(line_shape(0.01), {});
  const auto grey = render_scan(sides, false, o);
  o.bit_depth = 16;
  const auto deep = render_scan(sides, false, o);
  EXPECT_EQ(deep.image.type(), CV_16U);
  cv::Mat scaled;
  deep.image.convertTo(scaled, CV_8U, 255.0 / 65535.0);
  EXPECT_LE(cv::norm(scaled, grey.image, cv::NORM_INF), 1.0);
  o.bit_depth = 8;
  o.colour = true;
  const auto colour = render_scan(sides, false, o);
  EXPECT_EQ(colour.image.type(), CV_8UC3);
  std::vector<cv::Mat> ch;
  cv::split(colour.image, ch);
  EXPECT_LE(cv::norm(ch[2], grey.image, cv::NORM_INF), 0.0);  // red channel carries the grey image
}

TEST(Render, InvalidOptionsAreRefused) {
  const auto sides = sample_shape(line_shape(0.01), {});
  RenderOptions o;
  o.mark_width_m = 0;
  EXPECT_THROW(render_scan(sides, false, o), Error);
  o = {};
  o.ink_level = 0.95;
  EXPECT_THROW(render_scan(sides, false, o), Error);
  o = {};
  o.bit_depth = 12;
  EXPECT_THROW(render_scan(sides, false, o), Error);
  o = {};
  o.dpi = 1e6;  // 10 mm at 10⁶ dpi is far above 200 Mpx
  EXPECT_THROW(render_scan(sides, false, o), Error);
  EXPECT_THROW(line_shape(-1), Error);
  EXPECT_THROW(sample_shape(line_shape(0.01), Wiggle{1e-4, 0, 1}), Error);
}

// The image is made in bands of 64 rows; the blur must not see the seams. Without noise, texture and
// shading, each pixel is paper·(1 − k·blurred coverage): drawn and blurred here on the whole image at
// once, it must equal the banded render to the grey level, across a band seam and the image's edges.
TEST(Render, BandsLeaveNoSeams) {
  RenderOptions o;
  o.noise = 0, o.texture = 0, o.shading = 0, o.margin_m = 0.3e-3, o.blur_px = 1.5;
  o.rotation_rad = 0.3;  // a slanted line through many band seams
  const auto scan = render_scan(sample_shape(line_shape(12e-3), {}), false, o);
  ASSERT_GT(scan.image.rows, 3 * 64);
  const double px_per_m = o.dpi / 0.0254;
  std::vector<Point2> polyline;
  for (const auto& p : scan.sides.front()) polyline.push_back(p * px_per_m);
  cv::Mat coverage = cv::Mat::zeros(scan.image.size(), CV_32F);
  draw_stroke_coverage(coverage, polyline, o.mark_width_m * px_per_m / 2);
  cv::GaussianBlur(coverage, coverage, cv::Size(0, 0), o.blur_px);
  const double k = 1 - o.ink_level / o.paper_level;
  int worst = 0;
  for (int y = 0; y < scan.image.rows; ++y) {
    for (int x = 0; x < scan.image.cols; ++x) {
      const double want = std::round(255 * o.paper_level * (1 - k * coverage.at<float>(y, x)));
      worst = std::max(worst, static_cast<int>(std::abs(want - scan.image.at<std::uint8_t>(y, x))));
    }
  }
  EXPECT_LE(worst, 1);
}

TEST(Render, FibreTextureHasTheDeviationAskedFor) {
  for (const double texture : {0.01, 0.03}) {
    RenderOptions o;
    o.noise = 0, o.shading = 0, o.texture = texture, o.margin_m = 8e-3, o.seed = 9;
    const auto scan = render_scan(sample_shape(line_shape(1e-3), {}), false, o);
    cv::Mat paper;
    scan.image(cv::Rect(0, 0, scan.image.cols, scan.image.rows / 3)).convertTo(paper, CV_64F, 1.0 / 255);
    cv::Scalar mean, sd;
    cv::meanStdDev(paper, mean, sd);
    EXPECT_NEAR(mean[0], o.paper_level, 0.005) << texture;
    EXPECT_NEAR(sd[0] / mean[0], texture, 0.15 * texture) << texture;  // quantisation adds 1/√12 grey levels
  }
}

TEST(Render, PlateMarksAndLabelsMustBeOnThePage) {
  Plate plate;
  plate.width_m = 30e-3, plate.height_m = 20e-3;
  plate.marks.push_back({sample_shape(line_shape(25e-3), {}), false});
  for (auto& p : plate.marks[0].sides[0]) p += Point2{2e-3, 10e-3};
  RenderOptions o;
  o.dpi = 300;
  EXPECT_NO_THROW(render_plate(plate, o));
  plate.marks[0].sides[0].back().x() = 29.95e-3;  // the spot's edge beyond the page
  EXPECT_THROW(render_plate(plate, o), Error);
  plate.marks[0].sides[0].back().x() = 27e-3;
  plate.labels.push_back({"A", {25e-3, 2e-3}, 4e-3});  // its top above the page
  EXPECT_THROW(render_plate(plate, o), Error);
}

// Rows written band by band read back as the same pixels, with the resolution in pHYs; an incomplete
// image is an error and leaves no file.
TEST(Render, PngRowWriterRoundTrips) {
  const auto dir = std::filesystem::temp_directory_path() / ("stiffpath_png_rows_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  cv::RNG rng(3);
  for (const int type : {CV_8UC1, CV_16UC1, CV_8UC3, CV_16UC3}) {
    cv::Mat image(150, 97, type);
    rng.fill(image, cv::RNG::UNIFORM, 0, CV_MAT_DEPTH(type) == CV_8U ? 256 : 65536);
    const auto path = dir / "rows.png";
    PngRowWriter png(path, image.cols, image.rows, type, 1200);
    for (int y = 0; y < image.rows; y += 64) png.write(image.rowRange(y, std::min(image.rows, y + 64)));
    png.commit();
    const cv::Mat back = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(back.type(), type);
    EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0.0) << "type " << type;
    const auto res = read_resolution(path);
    ASSERT_TRUE(res.has_value());
    EXPECT_EQ(res->dpi_x, 1200.0);
  }
  const auto partial = dir / "partial.png";
  {
    PngRowWriter png(partial, 10, 10, CV_8UC1, 600);
    png.write(cv::Mat(4, 10, CV_8UC1, cv::Scalar(7)));
    EXPECT_THROW(png.commit(), Error);
    EXPECT_THROW(png.write(cv::Mat(4, 11, CV_8UC1)), Error);  // not the image's width
  }
  EXPECT_FALSE(std::filesystem::exists(partial));
  for (const auto& entry : std::filesystem::directory_iterator(dir)) EXPECT_EQ(entry.path().filename(), "rows.png");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace stiffpath::vision
