// Corner blending (G64 P): fillet geometry by hand, and blended programs staying within their tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

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
      const double t = seg.start_time_s + seg.profile.duration_s * k / 2000;
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
  for (std::size_t k = 0; k + 1 < t.segments().size(); ++k) EXPECT_GT(t.segments()[k].profile.end_velocity_m_s, 0.0);
}

TEST(CornerBlend, G61SquareStopsExactlyAtEachCorner) {
  const Trajectory t = test::plan_text("G0 X200 Y-20\nG61 G1 X240 F12000\nY20\nX200\n");
  ASSERT_EQ(t.segments().size(), 3u);
  for (const auto& seg : t.segments()) {
    EXPECT_EQ(seg.profile.start_velocity_m_s, 0.0);
    EXPECT_EQ(seg.profile.end_velocity_m_s, 0.0);
  }
  EXPECT_EQ(t.evaluate(t.segments()[0].end_time_s()).position_m, Vec2(0.240, -0.020));
}

TEST(CornerBlend, NoBlendWhereTheLaserSwitches) {
  const Trajectory t = test::plan_text("G0 X200 Y-20\nG64 P0.5\nM3 S100\nG0 X220\nG1 Y0 F3000\n");
  ASSERT_EQ(t.segments().size(), 2u);  // G0 (laser off) then G1 (laser on): the mark starts at the corner
  EXPECT_EQ(t.segments()[1].path.start_m, Vec2(0.220, -0.020));
}

}  // namespace
}  // namespace stiffpath::motion
