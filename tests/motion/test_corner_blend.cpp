// Corner blending (G64 P): fillet geometry by hand, and blended programs staying within their tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "chord_programs.hpp"
#include "planner_checks.hpp"
#include "stiffpath/motion/corner_blend.hpp"

namespace stiffpath::motion {
namespace {

TEST(CornerFillet, RightAngleByHand) {
  // 90° left turn at the origin, 10 µm tolerance: r·(√2 − 1) = 10 µm, trim = r·tan 45° = r.
  const auto f = corner_fillet(Vec2::Zero(), Vec2::UnitX(), Vec2::UnitY(), 10e-6, 1.0);
  ASSERT_TRUE(f.has_value());
  const double r = 10e-6 / (std::sqrt(2.0) - 1.0);
  EXPECT_NEAR(f->radius_m, r, 1e-18);
  EXPECT_NEAR(f->trim_m, r, 1e-18);
  EXPECT_TRUE(f->entry_m.isApprox(Vec2(-r, 0.0)));
  EXPECT_TRUE(f->exit_m.isApprox(Vec2(0.0, r)));
  EXPECT_TRUE(f->center_m.isApprox(Vec2(-r, r)));
  EXPECT_NEAR(f->sweep_rad, std::numbers::pi / 2, 1e-15);
  // The arc's midpoint is exactly the tolerance away from the corner.
  const Vec2 mid = f->center_m + r * Vec2(std::cos(-std::numbers::pi / 4), std::sin(-std::numbers::pi / 4));
  EXPECT_NEAR(mid.norm(), 10e-6, 1e-18);
}

TEST(CornerFillet, RightTurnShortLinesAndReversal) {
  const auto f = corner_fillet(Vec2::Zero(), Vec2::UnitX(), -Vec2::UnitY(), 1e-3, 2e-4);  // room for 0.2 mm only
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->trim_m, 2e-4, 1e-18);
  EXPECT_LT(f->sweep_rad, 0.0);
  EXPECT_LT(f->radius_m * (std::sqrt(2.0) - 1.0), 1e-3);  // deviation below the tolerance
  EXPECT_FALSE(corner_fillet(Vec2::Zero(), Vec2::UnitX(), -Vec2::UnitX(), 1e-3, 1.0).has_value());
  EXPECT_FALSE(corner_fillet(Vec2::Zero(), Vec2::UnitX(), Vec2::UnitY(), 0.0, 1.0).has_value());
}

// Smallest distance from a point to the sampled path.
double closest_approach(const Trajectory& trajectory, const Vec2& point) {
  double best = INFINITY;
  for (const auto& seg : trajectory.segments()) {
    for (int k = 0; k <= 2000; ++k) {
      const double t = seg.start_time_s + seg.duration_s * k / 2000;
      best = std::min(best, (evaluate(seg, t).position_m - point).norm());
    }
  }
  return best;
}

TEST(CornerBlend, G64SquareRoundsEachCornerWithinItsToleranceWithoutStopping) {
  const std::string square = "G0 X200 Y-20\nM3 S100\nG64 P0.05\nG1 X240 F12000\nY20\nX200\nY-20\nM2\n";
  const Trajectory t = test::plan_text(square);
  test::expect_within_limits(t, MotionLimits{});
  test::expect_continuous_junctions(t, MotionLimits{});
  int arcs = 0;
  for (const auto& seg : t.segments()) arcs += seg.path.kind == SegmentKind::arc;
  EXPECT_EQ(arcs, 3);  // the corners at (240, −20), (240, 20) and (200, 20); the job ends at (200, −20)
  for (const Vec2& corner : {Vec2(0.240, -0.020), Vec2(0.240, 0.020), Vec2(0.200, 0.020)}) {
    const double d = closest_approach(t, corner);
    EXPECT_LE(d, 0.05e-3 * (1 + 1e-6));
    EXPECT_GT(d, 0.04e-3);  // the tolerance is used, not wasted
  }
  for (std::size_t k = 0; k + 1 < t.segments().size(); ++k) EXPECT_GT(t.segments()[k].exit_speed_m_s, 0.0);
}

TEST(CornerBlend, G61SquareStopsExactlyAtEachCorner) {
  const Trajectory t = test::plan_text("G0 X200 Y-20\nG61 G1 X240 F12000\nY20\nX200\n");
  ASSERT_EQ(t.segments().size(), 3u);
  for (const auto& seg : t.segments()) {
    EXPECT_EQ(seg.entry_speed_m_s, 0.0);
    EXPECT_EQ(seg.exit_speed_m_s, 0.0);
  }
  EXPECT_EQ(t.evaluate(t.segments()[0].end_time_s()).position_m, Vec2(0.240, -0.020));
}

TEST(CornerBlend, NoBlendWhereTheLaserSwitches) {
  const Trajectory t = test::plan_text("G0 X200 Y-20\nG64 P0.5\nM3 S100\nG0 X220\nG1 Y0 F3000\n");
  ASSERT_EQ(t.segments().size(), 2u);  // G0 (laser off) then G1 (laser on): the mark starts at the corner
  EXPECT_EQ(t.segments()[1].path.start_m, Vec2(0.220, -0.020));
}

TEST(CornerBlend, ChordsBecomeAChainOfTangentArcsWithoutShortLinesBetween) {
  // A circle of 0.1 mm chords, coordinates rounded to 0.1 µm: neighbouring chords differ by a few
  // tenths of a µm, so two blends of one chord leave nm-long lines between their arcs. Each joins
  // the following arc, which then starts where the line did, turned by at most a quarter of the
  // corner angle: what remains is a chain of arcs whose junctions are all tangent.
  std::istringstream in(test::chord_circle(222.132, 0.0, 5.0, 0.1, 12000.0));
  GcodeReader reader(in, "job.gcode");
  const double corner = JunctionRules{}.corner_angle_rad;
  CornerBlender blender(reader, corner);
  std::vector<PathSegment> segs;
  while (auto s = blender.next()) segs.push_back(*s);
  int arcs = 0;
  for (std::size_t k = 0; k < segs.size(); ++k) {
    arcs += segs[k].kind == SegmentKind::arc;
    if (segs[k].kind == SegmentKind::line) {
      EXPECT_GT(segs[k].length_m, 1e-6) << "segment " << k;
    }
    if (k + 1 < segs.size()) {
      EXPECT_EQ(segs[k].end_m, segs[k + 1].start_m);
      EXPECT_LE(turn_angle_rad(end_tangent(segs[k]), start_tangent(segs[k + 1])), 0.25 * corner) << "segment " << k;
    }
  }
  EXPECT_GT(arcs, 300);  // one per chord corner (315 chords)
}

TEST(CornerFillet, ArcAbsorbingALineStartsOnItAndEndsTangentAtTheExit) {
  // A 90° fillet of radius 1 mm at the origin, preceded by 2 µm of line from (−1.002, 0) mm.
  const auto f = corner_fillet(Vec2::Zero(), Vec2::UnitX(), Vec2::UnitY(), 1e-3 * (std::sqrt(2.0) - 1.0), 1.0);
  ASSERT_TRUE(f.has_value());
  const Vec2 start(-1.002e-3, 0.0);
  const auto arc = arc_absorbing_line(start, Vec2::UnitX(), *f, 0.1);
  ASSERT_TRUE(arc.has_value());
  EXPECT_EQ(arc->start_m, start);
  EXPECT_EQ(arc->end_m, f->exit_m);
  EXPECT_NEAR((arc->start_m - arc->center_m).norm(), (arc->end_m - arc->center_m).norm(), 1e-15);
  EXPECT_LT(turn_angle_rad(end_tangent(*arc), Vec2::UnitY()), 1e-12);  // tangent to the next line
  // It turns away from the line at its start by about length·curvature = 2 µm / 1 mm = 2 mrad.
  EXPECT_NEAR(turn_angle_rad(Vec2::UnitX(), start_tangent(*arc)), 2e-3, 2e-5);
  EXPECT_FALSE(arc_absorbing_line(start, Vec2::UnitX(), *f, 1e-3).has_value());
}

}  // namespace
}  // namespace stiffpath::motion
