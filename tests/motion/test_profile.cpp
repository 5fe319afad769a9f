// Profile solver: rest-to-rest durations against closed forms, hand-checked cases, statuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "stiffpath/motion/profile.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {
namespace {

Profile solve(double length, double v0, double v1, double v, double a, double j) {
  Profile p;
  const ProfileStatus status = solve_profile({length, v0, v1, v, a, j}, p);
  EXPECT_EQ(status, ProfileStatus::ok) << describe(status);
  return p;
}

// Rest-to-rest double-S durations, derived independently (Biagiotti & Melchiorri, Trajectory
// Planning for Automatic Machines and Robots, §3.4, with zero boundary speeds):
double rest_to_rest_duration(double L, double v, double a, double j) {
  const bool a_reached_at_v = v * j >= a * a;                  // does reaching v need the plateau?
  const double d_to_v = a_reached_at_v ? v * (v / a + a / j)   // distance to reach v and stop again
                                       : 2.0 * v * std::sqrt(v / j);
  if (L >= d_to_v) return L / v + (a_reached_at_v ? v / a + a / j : 2.0 * std::sqrt(v / j));
  if (L >= 2.0 * a * a * a / (j * j)) {                        // a reached, v not: peak from a quadratic
    const double vp = 0.5 * (-a * a / j + std::sqrt(a * a * a * a / (j * j) + 4.0 * a * L));
    return 2.0 * (vp / a + a / j);
  }
  return 4.0 * std::cbrt(L / (2.0 * j));                       // neither: four jerk ramps of (L/2j)^(1/3)
}

TEST(Profile, RestToRestDurationsMatchClosedFormsInAllFourCases) {
  const double a = 49.03325, j = 9806.65;
  struct Case { double L, v; const char* what; };
  const Case cases[] = {
      {0.100, 2.0, "v and a reached (thesis x motion)"},
      {0.150, 2.0, "v and a reached (thesis y motion)"},
      {0.050, 0.2, "v reached, a not (v·j < a²)"},
      {0.050, 5.0, "a reached, v not"},
      {0.0002, 5.0, "neither reached"},
      {1e-9, 2.0, "a nanometre"},
  };
  for (const Case& c : cases) {
    const Profile p = solve(c.L, 0.0, 0.0, c.v, a, j);
    EXPECT_NEAR(p.duration_s, rest_to_rest_duration(c.L, c.v, a, j), 1e-12 * (1.0 + p.duration_s)) << c.what;
    const ProfileState end = p.state_at(p.duration_s);
    EXPECT_EQ(end.s_m, c.L);
    EXPECT_EQ(end.v_m_s, 0.0);
  }
}

TEST(Profile, HandCheckedThesisXMotion) {
  // 100 mm at 2 m/s, 5 g, 5 ms ramps: speed-up takes 2/49.03 + 0.005 = 45.79 ms over 45.79 mm;
  // the same to stop, so 8.42 mm of cruise (4.21 ms): 95.79 ms in all.
  const double a = 5 * 9.80665, j = a / 0.005;
  const Profile p = solve(0.1, 0.0, 0.0, 2.0, a, j);
  const double ramp = 2.0 / a + 0.005;
  EXPECT_NEAR(p.phase_s[0], 0.005, 1e-15);
  EXPECT_NEAR(p.phase_s[1], 2.0 / a - 0.005, 1e-15);
  EXPECT_NEAR(p.phase_s[3], (0.1 - 2.0 * ramp) / 2.0, 1e-14);
  EXPECT_NEAR(p.duration_s, 2.0 * ramp + (0.1 - 2.0 * ramp) / 2.0, 1e-14);
  EXPECT_DOUBLE_EQ(p.peak_velocity_m_s, 2.0);
  const ProfileState mid = p.state_at(p.duration_s / 2);
  EXPECT_NEAR(mid.s_m, 0.05, 1e-15);
  EXPECT_EQ(mid.a_m_s2, 0.0);
}

TEST(Profile, OnlyAccelerationAndOnlyDeceleration) {
  const double a = 49.0, j = 9800.0, L = 0.01;
  const double v_end = reachable_speed(L, 0.2, a, j);
  const Profile up = solve(L, 0.2, v_end, 10.0, a, j);
  EXPECT_NEAR(up.peak_velocity_m_s, v_end, 1e-12);
  EXPECT_EQ(up.phase_s[4] + up.phase_s[5] + up.phase_s[6], 0.0);
  const Profile down = solve(L, v_end, 0.2, 10.0, a, j);
  EXPECT_NEAR(down.peak_velocity_m_s, v_end, 1e-12);
  EXPECT_EQ(down.phase_s[0] + down.phase_s[1] + down.phase_s[2], 0.0);
  EXPECT_NEAR(down.duration_s, up.duration_s, 1e-15);
  Profile unused;
  EXPECT_EQ(solve_profile({L * 0.99, 0.2, v_end, 10.0, a, j}, unused), ProfileStatus::unreachable);
}

TEST(Profile, EqualBoundarySpeedsWithShortLengthRiseAboveThem) {
  const Profile p = solve(0.001, 0.3, 0.3, 2.0, 49.0, 9800.0);
  EXPECT_GT(p.peak_velocity_m_s, 0.3);
  EXPECT_LT(p.phase_s[3], 1e-15);  // no cruise beyond rounding
  EXPECT_NEAR(p.phase_s[0], p.phase_s[6], 1e-15);  // symmetric
  // Cruise case: long enough to reach the limit exactly.
  const Profile q = solve(1.0, 0.3, 0.3, 0.5, 49.0, 9800.0);
  EXPECT_EQ(q.peak_velocity_m_s, 0.5);
  EXPECT_GT(q.phase_s[3], 1.9);
}

TEST(Profile, InvalidInputsAreRefused) {
  Profile p;
  EXPECT_EQ(solve_profile({-1.0, 0, 0, 1, 1, 1}, p), ProfileStatus::invalid_input);
  EXPECT_EQ(solve_profile({1.0, 2.0, 0, 1, 1, 1}, p), ProfileStatus::invalid_input);  // start above the limit
  EXPECT_EQ(solve_profile({1.0, 0, 0, 1, 0, 1}, p), ProfileStatus::invalid_input);
  EXPECT_EQ(solve_profile({1.0, 0, 0, 1, 1, NAN}, p), ProfileStatus::invalid_input);
  EXPECT_EQ(solve_profile({INFINITY, 0, 0, 1, 1, 1}, p), ProfileStatus::invalid_input);
  EXPECT_STREQ(describe(ProfileStatus::unreachable), "end speed unreachable within the length");
}

TEST(Profile, ZeroLengthAtRestTakesNoTime) {
  const Profile p = solve(0.0, 0.0, 0.0, 1.0, 1.0, 1.0);
  EXPECT_EQ(p.duration_s, 0.0);
  EXPECT_EQ(p.state_at(1.0).s_m, 0.0);
}

TEST(SpeedChange, ReachableSpeedInvertsTheDistance) {
  // The distance is monotone in the end speed, so the answer is right when the distances of the
  // neighbouring speeds a few ulps below and above bracket the length (for large v0 and tiny L the
  // speed gain is below one ulp of v0, so the distance itself cannot be matched more closely).
  const double a = 49.0, j = 9800.0, eps = 4.0 * std::numeric_limits<double>::epsilon();
  for (const double v0 : {0.0, 1e-6, 0.01, 0.3, 2.0, 20.0}) {
    for (const double L : {1e-9, 1e-6, 1e-4, 1e-3, 0.01, 0.1, 1.0}) {
      const double v = reachable_speed(L, v0, a, j);
      ASSERT_GE(v, v0);
      const double below = std::max(v0, v * (1.0 - eps) - 1e-300), above = v * (1.0 + eps) + 1e-300;
      EXPECT_LE(speed_change(v0, below, a, j).distance_m, L) << "v0 " << v0 << " L " << L;
      EXPECT_GE(speed_change(v0, above, a, j).distance_m, L) << "v0 " << v0 << " L " << L;
      EXPECT_LE(speed_change(below, v0, a, j).distance_m, L);  // symmetric: the same backwards
    }
  }
}

}  // namespace
}  // namespace stiffpath::motion
