// Fiducials (rings with a cross) found on rendered plates at the renderer's centres, and refused with the reason when missing or ambiguous.
#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/render/render.hpp"
#include "stiffpath/vision/scan/fiducials.hpp"

namespace stiffpath::vision {
namespace {

constexpr double kPi = std::numbers::pi;

// A 40 × 30 mm page with fiducials at `centres` (mm, page frame), a line and a label, on a 50 × 40 mm bed.
Plate plate_with(const std::vector<Point2>& centres_mm, const FiducialShape& shape, double angle_deg, bool mirror) {
  Plate plate;
  plate.width_m = 40e-3;
  plate.height_m = 30e-3;
  for (const auto& c : centres_mm) plate.fiducials.push_back({c * 1e-3, shape});
  PlateMarkPath line{sample_shape(line_shape(20e-3), {}), false};
  for (auto& p : line.sides.front()) p += Point2{10e-3, 14e-3};
  plate.marks.push_back(line);
  plate.labels = {{"O", {17e-3, 23e-3}, 5.5e-3}};  // a round letter the size of a ring: not a fiducial
  ScannerBed bed;
  bed.width_m = 50e-3;
  bed.height_m = 40e-3;
  bed.page_at_m = {5e-3, 4e-3};
  bed.page_angle_rad = angle_deg * kPi / 180;
  bed.mirror = mirror;
  bed.smudges = 4;
  plate.bed = bed;
  return plate;
}

RenderOptions noisy(std::uint64_t seed) {
  RenderOptions o;
  o.texture = 0.01;
  o.noise = 0.01;
  o.seed = seed;
  return o;
}

// Found where the renderer drew them, to well under a micrometre, with an uncertainty that covers the error.
TEST(Fiducials, RingsWithACrossAreFoundAtTheirCentresOnATurnedAndMirroredPage) {
  const std::vector<Point2> centres{{5, 5}, {35, 5}, {5, 25}, {35, 25}};
  struct Case {
    double angle_deg;
    bool mirror;
    std::uint64_t seed;
  };
  for (const Case& c : {Case{0.0, false, 91}, Case{1.7, false, 92}, Case{-0.8, true, 93}}) {
    const RenderedPlate rendered = render_plate(plate_with(centres, {}, c.angle_deg, c.mirror), noisy(c.seed));
    FiducialSearch search;
    search.expected = 4;
    const auto found = find_fiducials(rendered.image, rendered.dpi, search);
    ASSERT_EQ(found.size(), 4u);
    for (const Fiducial& f : found) {
      double nearest = 1;
      for (const auto& t : rendered.fiducials_m) nearest = std::min(nearest, (t - f.centre_m).norm());
      std::printf("[accuracy] fiducial at (%.3f, %.3f) mm, page at %+.1f deg%s: centre error %.3f um, stated uncertainty %.3f um, "
                  "radius %.4f mm\n", f.centre_m.x() * 1e3, f.centre_m.y() * 1e3, c.angle_deg, c.mirror ? " mirrored" : "", nearest * 1e6,
                  f.uncertainty_m * 1e6, f.radius_m * 1e3);
      EXPECT_LT(nearest, 1e-6);
      EXPECT_LE(nearest, 3 * std::sqrt(2.0) * f.uncertainty_m);  // both axes: within three standard uncertainties
      EXPECT_NEAR(f.radius_m, 3e-3, 2e-6);
      EXPECT_NEAR(f.width_m, 0.2e-3, 0.01e-3);
      EXPECT_TRUE(f.cross);
    }
  }
}

// Rings without a cross, of another size.
TEST(Fiducials, PlainRingsOfAnyRadius) {
  FiducialShape ring;
  ring.ring_radius_m = 2e-3;
  ring.cross = false;
  const RenderedPlate rendered = render_plate(plate_with({{5, 5}, {35, 6}, {30, 24}}, ring, 0.4, false), noisy(94));
  FiducialSearch search;
  search.shape = ring;
  search.expected = 3;
  const auto found = find_fiducials(rendered.image, rendered.dpi, search);
  ASSERT_EQ(found.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    double nearest = 1;
    for (const auto& t : rendered.fiducials_m) nearest = std::min(nearest, (t - found[k].centre_m).norm());
    EXPECT_LT(nearest, 1e-6);
  }
}

std::string refusal(const RenderedPlate& rendered, const FiducialSearch& search) {
  try {
    (void)find_fiducials(rendered.image, rendered.dpi, search);
  } catch (const Error& e) {
    return e.what();
  }
  return "accepted";
}

// Missing, ambiguous, broken or of the wrong kind: refused, with what was found and why the rest was not.
TEST(Fiducials, MissingAmbiguousOrWrongRingsAreRefusedWithTheReason) {
  FiducialSearch search;
  search.expected = 3;
  const RenderedPlate two = render_plate(plate_with({{5, 5}, {35, 5}}, {}, 0.0, false), noisy(95));
  const std::string missing = refusal(two, search);
  EXPECT_NE(missing.find("fiducials missing: found 2"), std::string::npos) << missing;
  EXPECT_NE(missing.find("of the 3"), std::string::npos) << missing;

  search.expected = 1;
  const std::string ambiguous = refusal(two, search);
  EXPECT_NE(ambiguous.find("fiducials ambiguous: found 2"), std::string::npos) << ambiguous;

  // Rings of 2 mm where 3 mm rings are expected, and rings without the cross where one is expected.
  FiducialShape small;
  small.ring_radius_m = 2.8e-3;
  small.cross_arm_m = 1.2e-3;
  const RenderedPlate wrong_size = render_plate(plate_with({{5, 5}, {35, 5}}, small, 0.0, false), noisy(96));
  search.expected = 2;
  search.radius_tolerance = 0.05;
  const std::string size = refusal(wrong_size, search);
  EXPECT_NE(size.find("a ring of radius 2.8"), std::string::npos) << size;
  FiducialShape plain;
  plain.cross = false;
  const RenderedPlate no_cross = render_plate(plate_with({{5, 5}, {35, 5}}, plain, 0.0, false), noisy(97));
  search.radius_tolerance = 0.1;
  const std::string cross = refusal(no_cross, search);
  EXPECT_NE(cross.find("without the cross"), std::string::npos) << cross;

  // A broken ring: a 300° arc with a cross (a C), beside a whole one.
  Plate plate = plate_with({{35, 5}}, {}, 0.0, false);
  PlateMarkPath arc;
  std::vector<Point2> points;
  for (int i = 0; i <= 600; ++i) {
    const double a = (30 + 300.0 * i / 600) * kPi / 180;
    points.push_back(Point2{5e-3, 5e-3} + 3e-3 * Point2{std::cos(a), std::sin(a)});
  }
  arc.sides = {points};
  plate.marks.push_back(arc);
  plate.marks.push_back({{{Point2{3.5e-3, 5e-3}, Point2{6.5e-3, 5e-3}}}, false});
  plate.marks.push_back({{{Point2{5e-3, 3.5e-3}, Point2{5e-3, 6.5e-3}}}, false});
  const std::string broken = refusal(render_plate(plate, noisy(98)), search);
  EXPECT_NE(broken.find("the ring is broken"), std::string::npos) << broken;
}

TEST(Fiducials, ShapesThatCannotBeDrawnAreRefused) {
  FiducialShape s;
  s.cross_arm_m = 2.7e-3;  // reaches within a width of the ring
  EXPECT_THROW(s.check("fiducial", 0.2e-3), Error);
  s.cross_arm_m = 1.5e-3;
  s.ring_radius_m = 0.1e-3;
  EXPECT_THROW(s.check("fiducial", 0.2e-3), Error);
  Plate plate = plate_with({{5, 5}}, {}, 0.0, false);
  plate.fiducials[0].at_m = {1e-3, 8e-3};  // its ring off the page
  EXPECT_THROW(render_plate(plate, noisy(99)), Error);
}

}  // namespace
}  // namespace stiffpath::vision
