// Corners: a G64 blend is never slower than the G61 stop it replaces (angles 10-170°, tolerances 0.01-2 mm,
// feeds 1-100 m/min, 1 g and 5 g), and its path stays within the tolerance of the two programmed lines.
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "planner_checks.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::motion {
namespace {

constexpr double deg = std::numbers::pi / 180.0;

// One corner at (222.132, 0) mm between two lines of `leg_mm`, the second turned by `turn_deg`.
std::string corner_program(double turn_deg, const std::string& mode, double feed_mm_min, double leg_mm) {
  const double in_x = 222.132 - leg_mm, in_y = 0.0;
  const double out_x = 222.132 + leg_mm * std::cos(turn_deg * deg), out_y = leg_mm * std::sin(turn_deg * deg);
  return fmt::format("G21 G90\nG0 X{:.6f} Y{:.6f}\nM3 S1000\n{}\nG1 X222.132 Y0 F{:g}\nG1 X{:.6f} Y{:.6f}\nM5\nM2\n", in_x,
                     in_y, mode, feed_mm_min, out_x, out_y);
}

// The largest distance from the path (64 points per planned segment) to the two programmed lines.
double deviation_m(const Trajectory& t, double turn_deg, double leg_mm) {
  const Vec2 corner(0.222132, 0.0), in = corner - Vec2(leg_mm * 1e-3, 0.0);
  const Vec2 out = corner + leg_mm * 1e-3 * Vec2(std::cos(turn_deg * deg), std::sin(turn_deg * deg));
  double worst = 0.0;
  for (const PlannedSegment& s : t.segments()) {
    for (int k = 0; k <= 64; ++k) {
      const Vec2 p = evaluate(s, s.start_time_s + s.duration_s * k / 64).position_m;
      worst = std::max(worst, std::min(distance_to_segment_m(p, in, corner), distance_to_segment_m(p, corner, out)));
    }
  }
  return worst;
}

TEST(CornerSweep, ABlendIsNeverSlowerThanTheStopItReplaces) {
  // The corner: 90°, 50 mm legs, 1 g, F60000. Before, G61 took 0.296 s and G64 P0.01 / P0.5 / P2
  // took 0.3015 / 0.3165 / 0.3225 s: the fillets' curvature step (v²·Δκ ≤ j·τ) held them below the speed a
  // stop costs.
  int cases = 0, faster = 0;
  double best_gain = 0.0;
  for (const double g : {1.0, 5.0}) {
    PlanOptions options;
    options.limits.max_acceleration_m_s2 = g * units::standard_gravity_m_s2;
    options.limits.max_jerk_m_s3 = default_jerk_m_s3(options.limits.max_acceleration_m_s2);
    for (const double turn : {10.0, 20.0, 45.0, 60.0, 90.0, 120.0, 150.0, 170.0}) {
      for (const double p_mm : {0.01, 0.05, 0.2, 0.5, 2.0}) {
        for (const double feed : {1000.0, 6000.0, 20000.0, 60000.0, 100000.0}) {
          const double leg = 50.0;
          SCOPED_TRACE(fmt::format("{:g} g, turn {:g}°, P {:g} mm, F {:g}", g, turn, p_mm, feed));
          const Trajectory stop = test::plan_text(corner_program(turn, "G61", feed, leg), options);
          const Trajectory blend = test::plan_text(corner_program(turn, fmt::format("G64 P{:g}", p_mm), feed, leg), options);
          ASSERT_LE(blend.duration_s(), stop.duration_s() * (1 + 1e-12));
          EXPECT_LE(deviation_m(blend, turn, leg), p_mm * 1e-3 * (1 + 1e-9));
          test::expect_within_limits(blend, options.limits, 8);
          test::expect_continuous_junctions(blend, options.limits);
          ++cases;
          const double gain = 1.0 - blend.duration_s() / stop.duration_s();
          faster += gain > 1e-3;
          best_gain = std::max(best_gain, gain);
          if (HasFatalFailure()) return;
        }
      }
    }
  }
  RecordProperty("faster", faster);
  RecordProperty("best_gain_percent", fmt::format("{:.1f}", 100 * best_gain));
  std::printf("corner sweep: %d of %d blends faster than the stop by more than 0.1 %%, best %.1f %%\n", faster, cases,
              100 * best_gain);
  EXPECT_EQ(cases, 400);
}

}  // namespace
}  // namespace stiffpath::motion
