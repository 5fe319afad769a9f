// Plates with several marks and labels: every mark measured against its own truth, labels set aside, regions of interest.
#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/render/render.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::vision {
namespace {

constexpr double kPi = std::numbers::pi;

// A small plate like the thesis's (fig. 4.7): a y line, an x line and a triangle with labels, shortened so
// the test stays quick (80 × 70 mm at 1200 dpi, 12.5 Mpx).
Plate small_plate() {
  Plate plate;
  plate.width_m = 80e-3;
  plate.height_m = 70e-3;
  auto placed = [](PathShape shape, const Wiggle& wiggle, double angle, Point2 at) {
    PlateMarkPath mark{sample_shape(shape, wiggle), shape.closed};
    const Point2 first = mark.sides.front().front();
    for (auto& side : mark.sides) {
      for (auto& p : side) {
        const Point2 d = p - first;
        p = at + Point2{std::cos(angle) * d.x() - std::sin(angle) * d.y(), std::sin(angle) * d.x() + std::cos(angle) * d.y()};
      }
    }
    return mark;
  };
  plate.marks.push_back(placed(line_shape(50e-3), {0.06e-3, 8e-3, 20e-3}, kPi / 2, {8e-3, 12e-3}));        // y motion
  plate.marks.push_back(placed(line_shape(40e-3), {0.04e-3, 6e-3, 20e-3}, 0.0, {20e-3, 64e-3}));           // x motion
  plate.marks.push_back(placed(triangle_shape(30e-3), {0.03e-3, 10e-3, 40e-3}, 0.01, {30e-3, 45e-3}));   // triangle
  plate.labels = {{"Y 5G", {10e-3, 9e-3}, 3e-3}, {"X 5G OC", {20e-3, 60e-3}, 3e-3}, {"TRI", {62e-3, 50e-3}, 3e-3}};
  return plate;
}

RenderOptions noisy() {
  RenderOptions o;
  o.noise = 0.01;
  o.texture = 0.01;
  o.specks = 15;
  o.seed = 51;
  return o;
}

// The plate's truth whose box holds the measured mark's box.
const PlateMarkTruth* truth_of(const RenderedPlate& rendered, const PlateMark& mark) {
  for (const auto& t : rendered.marks) {
    const cv::Rect2d grown(t.box_m.x - 0.5e-3, t.box_m.y - 0.5e-3, t.box_m.width + 1e-3, t.box_m.height + 1e-3);
    if ((grown & mark.box_m) == mark.box_m) return &t;
  }
  return nullptr;
}

TEST(Plate, EveryMarkIsMeasuredAgainstItsOwnTruthAndTheLabelsAreSetAside) {
  const auto rendered = render_plate(small_plate(), noisy());
  ScanOptions o;
  o.sides = 0;  // find each mark's shape
  const PlateResult plate = analyse_plate(rendered.image, rendered.dpi, o);
  ASSERT_EQ(plate.marks.size(), 3u);
  EXPECT_EQ(plate.labels.size(), 3u);  // one area per label, however many letters
  int letters = 0;
  for (const auto& l : plate.labels) letters += l.features;
  EXPECT_GE(letters, 10);
  std::vector<std::string> got;
  for (const auto& m : plate.marks) {
    ASSERT_TRUE(m.measured) << "mark " << m.index << ": " << m.reason;
    const PlateMarkTruth* t = truth_of(rendered, m);
    ASSERT_NE(t, nullptr) << "mark " << m.index << " matches no drawn path";
    got.push_back(shape_name(m.result));
    EXPECT_EQ(m.result.metrics.closed, t->closed);
    EXPECT_EQ(m.result.metrics.sides.size(), t->truth.sides.size());
    std::printf("[accuracy] plate mark %d (%s): length %.4f mm, error %+.2f um\n", m.index, got.back().c_str(),
                t->truth.length_m * 1e3, (m.result.metrics.length_m - t->truth.length_m) * 1e6);
    EXPECT_NEAR(m.result.metrics.length_m, t->truth.length_m, 5e-6 * static_cast<double>(t->truth.sides.size()));
    EXPECT_NEAR(m.result.metrics.deviation_area_m2, t->truth.deviation_area_m2, 0.03 * t->truth.deviation_area_m2 + 0.02e-6);
  }
  // Reading order of their top edges: the y line (top 12 mm), the triangle (apex near 19 mm), the x line.
  EXPECT_EQ(got, (std::vector<std::string>{"line", "triangle", "line"}));
  const nlohmann::json json = to_json(plate);
  EXPECT_EQ(json["measured"], 3);
  EXPECT_EQ(json["skipped"], 0);
  EXPECT_EQ(json["marks"][1]["shape"], "triangle");
  EXPECT_EQ(json["marks"][1]["box_mm"].size(), 4u);
  EXPECT_EQ(json["labels"].size(), 3u);
}

TEST(Plate, ARegionPicksOneMarkAndKeepsTheImageFrame) {
  const auto rendered = render_plate(small_plate(), noisy());
  const PlateResult plate = analyse_plate(rendered.image, rendered.dpi, [] {
    ScanOptions o;
    o.sides = 0;
    return o;
  }());
  const PlateMark& triangle = plate.marks[1];
  ASSERT_TRUE(triangle.measured);
  // A region around the triangle (2 mm of paper around its box), analysed as a single scan.
  const double px_per_m = rendered.dpi / 0.0254;
  ScanOptions o;
  o.sides = 3;
  o.roi_px = cv::Rect(cv::Point(static_cast<int>((triangle.box_m.x - 2e-3) * px_per_m), static_cast<int>((triangle.box_m.y - 2e-3) * px_per_m)),
                      cv::Point(static_cast<int>((triangle.box_m.x + triangle.box_m.width + 2e-3) * px_per_m),
                                static_cast<int>((triangle.box_m.y + triangle.box_m.height + 2e-3) * px_per_m)));
  const ScanResult r = analyse_scan(rendered.image, rendered.dpi, o);
  ASSERT_TRUE(r.metrics.closed);
  for (std::size_t k = 0; k < 3; ++k) {
    // The same corners in the same (whole image's) frame, to the noise of the separate background.
    EXPECT_LT((r.metrics.corners[k].position - triangle.result.metrics.corners[k].position).norm(), 2e-6) << k;
  }
  EXPECT_NEAR(r.metrics.length_m, triangle.result.metrics.length_m, 3e-6);
  // A region that cuts a mark is refused as a cut-off mark, naming the region.
  o.roi_px.width /= 2;
  try {
    analyse_scan(rendered.image, rendered.dpi, o);
    ADD_FAILURE() << "a mark cut by the region was measured";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("border of the region"), std::string::npos) << e.what();
  }
  // A region beyond the image is refused.
  o.roi_px = cv::Rect(rendered.image.cols - 10, 0, 20, 20);
  EXPECT_THROW(analyse_scan(rendered.image, rendered.dpi, o), Error);
}

TEST(Plate, ASingleMarkScanOfAPlateSaysHowToPickOne) {
  const auto rendered = render_plate(small_plate(), noisy());
  try {
    analyse_scan(rendered.image, rendered.dpi, {});
    ADD_FAILURE() << "a plate was measured as one mark";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("found two separate marks"), std::string::npos) << what;
    EXPECT_NE(what.find("--roi"), std::string::npos) << what;
    EXPECT_NE(what.find("--all-marks"), std::string::npos) << what;
  }
}

TEST(Plate, LargeLetteringAndCrossesAreSkippedWithTheReason) {
  Plate plate;
  plate.width_m = 70e-3;
  plate.height_m = 45e-3;
  plate.marks.push_back({sample_shape(line_shape(30e-3), {}), false});
  for (auto& p : plate.marks[0].sides[0]) p += Point2{5e-3, 8e-3};
  // An X of two strokes crossing at their middles: one dark feature, neither a line nor a chain of sides.
  plate.marks.push_back({sample_shape({{{45e-3, 5e-3}, {60e-3, 20e-3}}, false}, {}), false});
  plate.marks.push_back({sample_shape({{{45e-3, 20e-3}, {60e-3, 5e-3}}, false}, {}), false});
  plate.labels = {{"OC", {8e-3, 38e-3}, 12e-3}};  // capitals 12 mm high: larger than the 10 mm minimum
  const auto rendered = render_plate(plate, noisy());
  ScanOptions o;
  o.sides = 0;
  const PlateResult r = analyse_plate(rendered.image, rendered.dpi, o);
  int measured = 0, skipped = 0;
  for (const auto& m : r.marks) {
    if (m.measured) {
      ++measured;
      EXPECT_EQ(shape_name(m.result), "line");
      EXPECT_NEAR(m.result.metrics.length_m, 30e-3, 5e-6);
    } else {
      ++skipped;
      EXPECT_FALSE(m.reason.empty());
      std::printf("[plate] mark %d skipped: %s\n", m.index, m.reason.c_str());
    }
  }
  EXPECT_EQ(measured, 1);
  EXPECT_GE(skipped, 2);  // the cross and the large letters (O, C)
}

}  // namespace
}  // namespace stiffpath::vision
