// fastest_speed_up: the bound on a profile's speed that lets runs join on release, against integration and solved profiles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "random_cases.hpp"
#include "stiffpath/motion/profile.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {
namespace {

// The fastest speed-up integrated step by step (jerk j until a, then a), read at distance s.
double integrated_speed_up(double s, double v0, double a_max, double j) {
  const double dt = 1e-7;
  double x = 0.0, v = v0, a = 0.0;
  while (x < s) {
    const double a_next = std::min(a + j * dt, a_max);
    const double v_next = v + 0.5 * (a + a_next) * dt;
    const double x_next = x + 0.5 * (v + v_next) * dt;
    if (x_next >= s) return v + (v_next - v) * (s - x) / (x_next - x);
    x = x_next, v = v_next, a = a_next;
  }
  return v;
}

TEST(SpeedBound, FastestSpeedUpMatchesStepByStepIntegration) {
  const double a = 49.03325, j = 9806.65;
  struct Case { double s, v0; };
  // Within the jerk ramp (from rest and moving) and past it, where the acceleration is held at a.
  for (const Case c : {Case{1e-5, 0.0}, Case{2e-4, 0.0}, Case{2e-4, 0.1}, Case{1e-3, 0.05}, Case{5e-3, 0.3}, Case{0.02, 1.0}}) {
    const double exact = fastest_speed_up(c.s, c.v0, a, j), integrated = integrated_speed_up(c.s, c.v0, a, j);
    EXPECT_NEAR(exact, integrated, 1e-6 * (1.0 + integrated)) << "s " << c.s << " v0 " << c.v0;
    EXPECT_GE(exact, c.v0);
  }
  EXPECT_EQ(fastest_speed_up(0.0, 0.25, a, j), 0.25);
}

TEST(SpeedBound, NoSolvedProfileIsFasterThanTheBoundFromEitherEnd) {
  // Random profiles of every shape (speed-up and slow-down, cruise or not, a reached or not): at
  // every sampled instant the speed lies at or below the bound from the entry forward and from the
  // exit back. Where the profile speeds up with jerk j from its entry the bound is reached, so it
  // is tight and not merely an upper bound.
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0, tight = 0;
  for (int c = 0; c < test::random_cases(4000); ++c) {
    const double a = 1.0 + 60.0 * unit(rng), j = a / (0.001 + 0.02 * unit(rng));
    const double vmax = 0.01 + 2.0 * unit(rng);
    const ProfileInput input{1e-5 + 0.05 * unit(rng), vmax * unit(rng), vmax * unit(rng), vmax, a, j};
    Profile p;
    if (solve_profile(input, p) != ProfileStatus::ok) continue;
    ++checked;
    double closest = 0.0;
    for (int k = 0; k <= 200; ++k) {
      const ProfileState state = p.state_at(p.duration_s * k / 200.0);
      const double forward = fastest_speed_up(state.s_m, input.start_velocity_m_s, a, j);
      const double backward = fastest_speed_up(input.length_m - state.s_m, input.end_velocity_m_s, a, j);
      ASSERT_LE(state.v_m_s, forward * (1.0 + 1e-9) + 1e-12) << "case " << c << " t " << k;
      ASSERT_LE(state.v_m_s, backward * (1.0 + 1e-9) + 1e-12) << "case " << c << " t " << k;
      if (k > 0 && state.s_m > 0.0) closest = std::max(closest, state.v_m_s / forward);
    }
    tight += closest > 1.0 - 1e-6;
  }
  EXPECT_GT(checked, test::random_cases(4000) / 2);
  EXPECT_GT(tight, checked / 10);
}

}  // namespace
}  // namespace stiffpath::motion
