// A plate on real paper: the page smaller than the scanner's bed, turned and moved on it, its edge, curl and smudges in view.
#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/render/render.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::vision {
namespace {

constexpr double kPi = std::numbers::pi;

PlateMarkPath placed_line(double length_m, double angle_rad, const Point2& at, const Wiggle& wiggle = {}) {
  PlateMarkPath mark{sample_shape(line_shape(length_m), wiggle), false};
  for (auto& p : mark.sides.front()) p = at + Point2{std::cos(angle_rad) * p.x() - std::sin(angle_rad) * p.y(), std::sin(angle_rad) * p.x() + std::cos(angle_rad) * p.y()};
  return mark;
}

// Two marks on a 45 × 35 mm page lying turned by `angle_deg` 5 mm into a 55 × 45 mm bed, smudged.
Plate page_on_bed(double angle_deg, bool mirror, int smudges) {
  Plate plate;
  plate.width_m = 45e-3;
  plate.height_m = 35e-3;
  plate.marks.push_back(placed_line(30e-3, 0.0, {6e-3, 10e-3}, {0.05e-3, 8e-3, 20e-3}));
  plate.marks.push_back(placed_line(20e-3, kPi / 2, {39e-3, 12e-3}));
  plate.labels = {{"X 5G", {6e-3, 8e-3}, 2.5e-3}};
  ScannerBed bed;
  bed.width_m = 55e-3;
  bed.height_m = 45e-3;
  bed.page_at_m = {5e-3, 5e-3};
  bed.page_angle_rad = angle_deg * kPi / 180;
  bed.mirror = mirror;
  bed.smudges = smudges;
  plate.bed = bed;
  return plate;
}

RenderOptions paper(std::uint64_t seed) {
  RenderOptions o;
  o.texture = 0.01;
  o.noise = 0.01;
  o.seed = seed;
  return o;
}

// The page's edge (a shadow on a brighter lid) and smudges are not marks: the plate shows its two marks, each
// measured to its truth, and the edge is listed as ignored, with the reason. Before, the page's outline was
// measured as a fifth, closed polyline mark (and on a plate cut by the scan, a line along the edge).
TEST(Paper, APageOnTheBedShowsItsTwoMarksAndNoMarkFromItsEdge) {
  struct Case {
    double angle_deg;
    bool mirror;
    std::uint64_t seed;
  };
  for (const Case& c : {Case{1.2, false, 81}, Case{-2.5, true, 82}, Case{0.0, false, 83}}) {
    const RenderedPlate rendered = render_plate(page_on_bed(c.angle_deg, c.mirror, 6), paper(c.seed));
    ScanOptions o;
    o.sides = 0;
    const PlateResult r = analyse_plate(rendered.image, rendered.dpi, o);
    ASSERT_EQ(r.marks.size(), 2u) << c.angle_deg;
    bool edge = false;
    for (const auto& i : r.ignored) edge = edge || i.reason.find("edge of the paper") != std::string::npos;
    EXPECT_TRUE(edge) << "the page's edge is not named among the ignored features";
    for (const auto& m : r.marks) {
      ASSERT_TRUE(m.measured) << m.reason;
      // Its truth: the drawn mark whose box holds the measured one's centre.
      const Point2 centre{m.box_m.x + m.box_m.width / 2, m.box_m.y + m.box_m.height / 2};
      const PlateMarkTruth* truth = nullptr;
      for (const auto& t : rendered.marks) {
        const cv::Rect2d grown(t.box_m.x - 1e-3, t.box_m.y - 1e-3, t.box_m.width + 2e-3, t.box_m.height + 2e-3);
        if (grown.contains(cv::Point2d(centre.x(), centre.y()))) truth = &t;
      }
      ASSERT_NE(truth, nullptr);
      const double err_um = (m.result.metrics.length_m - truth->truth.length_m) * 1e6;
      std::printf("[accuracy] page on the bed at %+.1f deg%s: mark of %.4f mm, error %+.2f um\n", c.angle_deg, c.mirror ? ", mirrored" : "",
                  truth->truth.length_m * 1e3, err_um);
      EXPECT_LE(std::abs(err_um), 5.0);
    }
  }
}

// One mark on a page on the bed, scanned as a single mark: measured, the edge set aside with a warning.
TEST(Paper, ASingleMarkOnAPageOnTheBedIsMeasuredAndTheEdgeSetAside) {
  Plate plate = page_on_bed(0.7, false, 3);
  plate.marks.erase(plate.marks.begin() + 1);
  plate.labels.clear();
  const RenderedPlate rendered = render_plate(plate, paper(84));
  const ScanResult r = analyse_scan(rendered.image, rendered.dpi, ScanOptions{});
  EXPECT_NEAR(r.metrics.length_m, rendered.marks[0].truth.length_m, 5e-6);
  bool named = false;
  for (const auto& w : r.warnings) named = named || w.find("edge of the paper") != std::string::npos;
  EXPECT_TRUE(named);
}

// A page with many smudges and no mark: nothing is taken for one.
TEST(Paper, SmudgesAloneAreNoMark) {
  Plate plate = page_on_bed(0.0, false, 40);
  plate.marks.clear();
  plate.labels.clear();
  RenderOptions o = paper(85);
  const RenderedPlate rendered = render_plate(plate, o);
  ScanOptions options;
  options.sides = 0;
  const PlateResult r = analyse_plate(rendered.image, rendered.dpi, options);
  EXPECT_TRUE(r.marks.empty()) << r.marks.size() << " marks, the first at x = " << r.marks.front().box_m.x * 1e3 << " mm";
  EXPECT_THROW(analyse_scan(rendered.image, rendered.dpi, ScanOptions{}), Error);
}

// The placement maps the page onto the image: a rigid motion (and a mirror), as the truth's boxes show.
TEST(Paper, ThePlacementTurnsMovesAndMirrorsThePage) {
  const Plate plate = page_on_bed(90.0, false, 0);
  const PagePlacement turned = page_placement(&*plate.bed);
  EXPECT_LT((turned.apply({10e-3, 0}) - Point2{5e-3, 15e-3}).norm(), 1e-12);  // x of the page runs down the bed
  ScannerBed mirrored = *plate.bed;
  mirrored.page_angle_rad = 0;
  mirrored.mirror = true;
  const PagePlacement m = page_placement(&mirrored);
  EXPECT_TRUE(m.mirrored());
  EXPECT_LT((m.apply({10e-3, 3e-3}) - Point2{55e-3 - 15e-3, 8e-3}).norm(), 1e-12);
}

}  // namespace
}  // namespace stiffpath::vision
