// Profile solver over seeded random inputs: limits, continuity, exact ends, and optimality by grid search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "random_cases.hpp"
#include "stiffpath/motion/profile.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {
namespace {

struct RandomInput {
  ProfileInput input;
  const char* shape;
};

RandomInput random_input(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ProfileInput in;
  in.max_velocity_m_s = 0.05 + 3.0 * unit(rng);
  in.max_acceleration_m_s2 = 1.0 + 60.0 * unit(rng);
  in.max_jerk_m_s3 = 50.0 * std::pow(400.0, unit(rng));  // 50 … 20 000 m/s³, log-uniform
  in.start_velocity_m_s = unit(rng) < 0.2 ? 0.0 : in.max_velocity_m_s * unit(rng);
  in.end_velocity_m_s = unit(rng) < 0.2 ? 0.0 : in.max_velocity_m_s * unit(rng);
  if (unit(rng) < 0.1) in.end_velocity_m_s = in.start_velocity_m_s;
  const double least = speed_change(in.start_velocity_m_s, in.end_velocity_m_s, in.max_acceleration_m_s2,
                                    in.max_jerk_m_s3).distance_m;
  const double pick = unit(rng);
  const char* shape = "general";
  if (pick < 0.1 && least > 0.0) {
    in.length_m = least;  // only acceleration or only deceleration is possible
    shape = "monotone";
  } else {
    in.length_m = least + std::pow(10.0, -6.0 + 6.0 * unit(rng));  // 1 µm … 1 m beyond the least
  }
  return {in, shape};
}

// Time of a speed change from v_from to v_to with jerk j whose acceleration is capped at `peak`
// (≤ the limit): a candidate of the family the grid search runs over.
double piece_time(double v_from, double v_to, double peak, double j) {
  const double dv = std::abs(v_to - v_from);
  return dv * j <= peak * peak ? 2.0 * std::sqrt(dv / j) : dv / peak + peak / j;
}

// Fine-grid search over 7-phase profiles: peak speed v_p, and the acceleration levels of both halves.
// Returns the least duration among candidates whose two halves fit in the length. The v_p grid is
// refined four times around the best candidate found so far (a zoom, not a guess from the solver).
double grid_search_duration(const ProfileInput& in) {
  const double v0 = in.start_velocity_m_s, v1 = in.end_velocity_m_s, j = in.max_jerk_m_s3;
  const double low = std::max(v0, v1), high = std::max(in.max_velocity_m_s, low);
  constexpr int n_speed = 200, n_accel = 12;
  double best = INFINITY, best_vp = low, from = low, to = high;
  for (int zoom = 0; zoom < 5; ++zoom) {
    const double step = (to - from) / n_speed;
    for (int k = 0; k <= n_speed; ++k) {
      const double vp = from + step * k;
      for (int m = 1; m <= n_accel; ++m) {
        const double peak_up = in.max_acceleration_m_s2 * m / n_accel;
        for (int n = 1; n <= n_accel; ++n) {
          const double peak_down = in.max_acceleration_m_s2 * n / n_accel;
          const double t_up = piece_time(v0, vp, peak_up, j), t_down = piece_time(vp, v1, peak_down, j);
          const double distance = 0.5 * (v0 + vp) * t_up + 0.5 * (vp + v1) * t_down;
          if (distance > in.length_m * (1 + 1e-12) || (vp <= 0.0 && in.length_m > 0.0)) continue;
          const double cruise = vp > 0.0 ? std::max(in.length_m - distance, 0.0) / vp : 0.0;
          if (t_up + t_down + cruise < best) {
            best = t_up + t_down + cruise;
            best_vp = vp;
          }
        }
      }
    }
    from = std::max(low, best_vp - step);
    to = std::min(high, best_vp + step);
  }
  return best;
}

void expect_within_limits_and_continuous(const ProfileInput& in, const Profile& p, int case_index) {
  const double v_lim = std::max(in.max_velocity_m_s, std::max(in.start_velocity_m_s, in.end_velocity_m_s));
  const double tol = 1e-9;
  const ProfileState start = p.state_at(0.0), end = p.state_at(p.duration_s);
  EXPECT_EQ(start.s_m, 0.0);
  EXPECT_EQ(start.v_m_s, in.start_velocity_m_s);
  EXPECT_EQ(start.a_m_s2, 0.0);
  EXPECT_EQ(end.s_m, in.length_m);
  EXPECT_EQ(end.v_m_s, in.end_velocity_m_s);
  constexpr int n = 500;
  ProfileState previous = start;
  const double dt = p.duration_s / n;
  for (int i = 1; i <= n; ++i) {
    const ProfileState s = p.state_at(i * dt);
    ASSERT_GE(s.v_m_s, -1e-12) << "case " << case_index;
    ASSERT_LE(s.v_m_s, v_lim * (1 + tol)) << "case " << case_index;
    ASSERT_LE(std::abs(s.a_m_s2), in.max_acceleration_m_s2 * (1 + tol)) << "case " << case_index;
    ASSERT_LE(std::abs(s.j_m_s3), in.max_jerk_m_s3 * (1 + tol)) << "case " << case_index;
    // Continuity: over one step, the changes are bounded by the next derivative's limit.
    ASSERT_LE(std::abs(s.a_m_s2 - previous.a_m_s2), in.max_jerk_m_s3 * dt * (1 + tol) + 1e-12) << "case " << case_index;
    ASSERT_LE(std::abs(s.v_m_s - previous.v_m_s), in.max_acceleration_m_s2 * dt * (1 + tol) + 1e-12) << "case " << case_index;
    ASSERT_LE(s.s_m - previous.s_m, v_lim * dt * (1 + tol) + 1e-15) << "case " << case_index;
    ASSERT_GE(s.s_m - previous.s_m, -1e-15) << "case " << case_index;
    previous = s;
  }
  // The phases join without jumps: evaluate just before and after each boundary.
  double boundary = 0.0;
  for (int k = 0; k < 6; ++k) {
    boundary += p.phase_s[k];
    const double h = 1e-7 * p.duration_s;
    if (boundary - h <= 0.0 || boundary + h >= p.duration_s) continue;
    const ProfileState before = p.state_at(boundary - h), after = p.state_at(boundary + h);
    EXPECT_NEAR(after.s_m, before.s_m, 2 * v_lim * h + 1e-15) << "case " << case_index << " boundary " << k;
    EXPECT_NEAR(after.v_m_s, before.v_m_s, 2 * in.max_acceleration_m_s2 * h + 1e-12) << "case " << case_index;
    EXPECT_NEAR(after.a_m_s2, before.a_m_s2, 2 * in.max_jerk_m_s3 * h + 1e-9) << "case " << case_index;
  }
}

TEST(ProfileRandom, WithinLimitsContinuousAndExactAtBothEnds) {
  std::mt19937_64 rng(20240501);
  const int cases = test::random_cases(3000);
  for (int c = 0; c < cases; ++c) {
    const RandomInput r = random_input(rng);
    Profile p;
    ASSERT_EQ(solve_profile(r.input, p), ProfileStatus::ok) << "case " << c << " (" << r.shape << ")";
    expect_within_limits_and_continuous(r.input, p, c);
    if (HasFatalFailure()) return;
  }
}

TEST(ProfileRandom, TimeAtInvertsTheArcLength) {
  std::mt19937_64 rng(606);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int c = 0; c < test::random_cases(2000); ++c) {
    const RandomInput r = random_input(rng);
    Profile p;
    ASSERT_EQ(solve_profile(r.input, p), ProfileStatus::ok);
    const double t = p.duration_s * unit(rng);
    const ProfileState state = p.state_at(t);
    const double back = p.time_at(state.s_m);
    // s(t) is flat only where v = 0 (at rest), so the time is recovered up to s's rounding over v.
    const double eps = std::numeric_limits<double>::epsilon();
    EXPECT_NEAR(p.state_at(back).s_m, state.s_m, 16 * eps * r.input.length_m + 1e-300) << "case " << c;
    if (state.v_m_s > 1e-6) {
      EXPECT_NEAR(back, t, 16 * eps * (r.input.length_m / state.v_m_s + p.duration_s)) << "case " << c;
    }
  }
  Profile p;
  ASSERT_EQ(solve_profile({0.1, 0.0, 0.0, 2.0, 49.03325, 9806.65}, p), ProfileStatus::ok);
  EXPECT_EQ(p.time_at(0.0), 0.0);
  EXPECT_EQ(p.time_at(0.1), p.duration_s);
  EXPECT_NEAR(p.time_at(0.05), 0.5 * p.duration_s, 1e-15);  // symmetric rest-to-rest profile
}

TEST(ProfileRandom, ReachableSpeedInvertsTheDistanceOverRandomInputs) {
  // As the hand-picked grid in test_profile.cpp: the distances of the speeds a few ulps below and
  // above the answer bracket the length, over random speeds, lengths (1 nm … 1 m) and limits.
  std::mt19937_64 rng(2718);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double eps = 4.0 * std::numeric_limits<double>::epsilon();
  for (int c = 0; c < test::random_cases(20000); ++c) {
    const double a = 1.0 + 60.0 * unit(rng), j = 50.0 * std::pow(400.0, unit(rng));
    const double v0 = unit(rng) < 0.2 ? 0.0 : 3.0 * unit(rng), L = std::pow(10.0, -9.0 + 9.0 * unit(rng));
    const double v = reachable_speed(L, v0, a, j);
    ASSERT_GE(v, v0) << "case " << c;
    const double below = std::max(v0, v * (1.0 - eps) - 1e-300), above = v * (1.0 + eps) + 1e-300;
    ASSERT_LE(speed_change(v0, below, a, j).distance_m, L) << "case " << c;
    ASSERT_GE(speed_change(v0, above, a, j).distance_m, L) << "case " << c;
  }
}

TEST(ProfileRandom, DerivativesAreConsistentWithFiniteDifferences) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int c = 0; c < test::random_cases(1000); ++c) {
    const RandomInput r = random_input(rng);
    Profile p;
    ASSERT_EQ(solve_profile(r.input, p), ProfileStatus::ok);
    const double t = p.duration_s * unit(rng), h = 1e-6 * p.duration_s;
    if (t - h < 0 || t + h > p.duration_s) continue;
    const ProfileState m = p.state_at(t - h), z = p.state_at(t), q = p.state_at(t + h);
    // Truncation error of the central difference plus the rounding of the differenced values.
    const double j = r.input.max_jerk_m_s3, eps = std::numeric_limits<double>::epsilon();
    EXPECT_NEAR((q.s_m - m.s_m) / (2 * h), z.v_m_s, j * h * h + 8 * eps * r.input.length_m / h) << "case " << c;
    EXPECT_NEAR((q.v_m_s - m.v_m_s) / (2 * h), z.a_m_s2, j * h + 8 * eps * z.v_m_s / h + 1e-12) << "case " << c;
  }
}

// Independent reference for the peak speed: bisection on the distance of the two halves, each
// from the closed forms T = 2·sqrt(Δv/j) (triangle) or Δv/a + a/j (trapezoid), distance (v₁+v₂)/2·T.
struct Half {
  double time, distance;
};
Half half(double from, double to, double a, double j) {
  const double dv = std::abs(to - from), t = dv * j <= a * a ? 2.0 * std::sqrt(dv / j) : dv / a + a / j;
  return {t, 0.5 * (from + to) * t};
}

double bisection_duration(const ProfileInput& in) {
  const double v0 = in.start_velocity_m_s, v1 = in.end_velocity_m_s, a = in.max_acceleration_m_s2,
               j = in.max_jerk_m_s3;
  const auto fits = [&](double vp) { return half(v0, vp, a, j).distance + half(vp, v1, a, j).distance <= in.length_m; };
  double lo = std::max(v0, v1), hi = std::max(in.max_velocity_m_s, lo);
  if (fits(hi)) {
    lo = hi;
  } else {
    for (int k = 0; k < 200 && hi - lo > 0.0; ++k) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (fits(mid) ? lo : hi) = mid;
    }
  }
  const Half up = half(v0, lo, a, j), down = half(lo, v1, a, j);
  return up.time + down.time + (lo > 0.0 ? std::max(in.length_m - up.distance - down.distance, 0.0) / lo : 0.0);
}

TEST(ProfileRandom, DurationsAgreeWithBisectionOnThePeakSpeedInEveryCase) {
  // Many inputs of the two cases below the acceleration limit (a quartic's root each): short
  // lengths, so that no cruise fits, over the varied limits of random_input.
  std::mt19937_64 rng(31337);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int cases = test::random_cases(20000);
  int two_triangles = 0, triangle_trapezoid = 0;
  for (int c = 0; c < cases; ++c) {
    ProfileInput in = random_input(rng).input;
    const double least = speed_change(in.start_velocity_m_s, in.end_velocity_m_s, in.max_acceleration_m_s2,
                                      in.max_jerk_m_s3).distance_m;
    if (c % 2 == 0) in.length_m = least + std::pow(10.0, -9.0 + 8.0 * unit(rng));
    Profile p;
    ASSERT_EQ(solve_profile(in, p), ProfileStatus::ok) << "case " << c;
    const double reference = bisection_duration(in);
    ASSERT_NEAR(p.duration_s, reference, 1e-12) << "case " << c;
    if (p.peak_velocity_m_s < in.max_velocity_m_s && p.phase_s[3] * p.peak_velocity_m_s <= 1e-12 * in.length_m) {
      const bool up = p.phase_s[1] > 0.0, down = p.phase_s[5] > 0.0;
      two_triangles += !up && !down && p.phase_s[0] > 0.0 && p.phase_s[4] > 0.0;
      triangle_trapezoid += up != down && p.phase_s[0] > 0.0 && p.phase_s[4] > 0.0;
    }
  }
  // The sweep reaches both quartic cases often (a tenth of the inputs each at least).
  EXPECT_GT(two_triangles, cases / 10);
  EXPECT_GT(triangle_trapezoid, cases / 20);
}

TEST(ProfileRandom, NoCandidateOfAFineGridSearchIsFaster) {
  std::mt19937_64 rng(4242);
  const int cases = std::max(40, test::random_cases(150) / 20);
  for (int c = 0; c < cases; ++c) {
    const RandomInput r = random_input(rng);
    Profile p;
    ASSERT_EQ(solve_profile(r.input, p), ProfileStatus::ok);
    const double grid = grid_search_duration(r.input);
    // The solver is never slower than any feasible candidate …
    EXPECT_LE(p.duration_s, grid * (1 + 1e-9) + 1e-15) << "case " << c << " (" << r.shape << ")";
    // … and the grid's best comes close to it (the grid is only as fine as its steps).
    EXPECT_LE(grid, p.duration_s * (1 + 1e-4) + 1e-12) << "case " << c << " (" << r.shape << ")";
  }
}

}  // namespace
}  // namespace stiffpath::motion
