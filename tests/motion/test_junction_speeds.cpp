// The look-ahead's speed rules against brute force: admissible entries and reachable exits of one segment.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "random_cases.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {
namespace {

// Brute force: can the speed change between v and w (either order) fit in L? Distances directly,
// with the distance's uncertainty from rounding the speeds (a few ulps of a tiny speed change make
// a relative error of about ulp(v)/Δv in the distance).
bool fits(double L, double v, double w, double a, double j) {
  const double lo = std::min(v, w), hi = std::max(v, w);
  const double uncertainty = hi > lo ? 4 * std::numeric_limits<double>::epsilon() * hi / (hi - lo) : 0.0;
  return speed_change(lo, hi, a, j).distance_m <= L * (1 + 1e-9 + uncertainty);
}

TEST(JunctionSpeeds, BrakingToRestCanBeShorterThanBrakingPartWay) {
  // The case that showed the rule: 0.1 mm, 5 g, 5 ms ramps. From 0.0485 m/s the segment can stop,
  // but cannot end at 0.0093 m/s.
  const double a = 49.03325, j = 9806.65, L = 1.08e-4;
  const double v = reachable_speed(L, 0.0, a, j);
  EXPECT_TRUE(fits(L, v, 0.0, a, j));
  EXPECT_FALSE(fits(L, v, 0.0093, a, j));
  EXPECT_EQ(max_entry_speed(L, 0.0093, a, j), v);
  const double exit = max_exit_speed(L, v, 0.0093, a, j);
  EXPECT_LT(exit, 0.0093);
  EXPECT_TRUE(fits(L, v, exit, a, j));
}

TEST(JunctionSpeeds, EntryAndExitRulesAgreeWithABruteForceScan) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr int grid = 4000;
  for (int c = 0; c < test::random_cases(300) / 3; ++c) {
    const double a = 5 + 60 * unit(rng), j = a / (0.002 + 0.02 * unit(rng));
    const double L = std::pow(10.0, -6 + 5 * unit(rng)), exit_max = 2.0 * unit(rng) * unit(rng);
    // Highest admissible entry: scan entries v and exits w ∈ [0, exit_max].
    const double entry = max_entry_speed(L, exit_max, a, j);
    auto admissible = [&](double v) {
      for (int k = 0; k <= grid; ++k) {
        if (fits(L, v, exit_max * k / grid, a, j)) return true;
      }
      return false;
    };
    EXPECT_TRUE(admissible(entry)) << "case " << c;
    EXPECT_FALSE(admissible(entry * 1.001 + 1e-9)) << "case " << c;
    // Highest exit from a random admissible entry.
    const double v = entry * unit(rng);
    const double exit = max_exit_speed(L, v, exit_max, a, j);
    ASSERT_LE(exit, exit_max);
    EXPECT_TRUE(fits(L, v, exit, a, j)) << "case " << c;
    double best = -1;
    for (int k = 0; k <= grid; ++k) {
      const double w = exit_max * k / grid;
      if (fits(L, v, w, a, j)) best = w;
    }
    EXPECT_GE(exit, best - 1e-12) << "case " << c << ": a scanned exit is faster";
  }
}

TEST(JunctionSpeeds, ExitBelowTheTargetIsTheHighestThatFits) {
  // The branch where braking from the entry v to the wanted exit does not fit but braking further
  // does: the entry is 70-100 % of the highest reachable from rest (so stopping fits) and the wanted
  // exit lies part-way down. The answer must fit and a speed 1e-6·v above it must not (unless that
  // passes the wanted exit), judged on distances, independently of the solver's own speed test.
  std::mt19937_64 rng(4711);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int in_branch = 0;
  for (int c = 0; c < test::random_cases(20000); ++c) {
    const double a = 1.0 + 60.0 * unit(rng), j = 50.0 * std::pow(400.0, unit(rng));
    const double L = std::pow(10.0, -7.0 + 6.0 * unit(rng));
    const double v = reachable_speed(L, 0.0, a, j) * (0.7 + 0.3 * unit(rng)), w = v * unit(rng);
    if (fits(L, v, w, a, j)) continue;
    ++in_branch;
    const double exit = max_exit_speed(L, v, w, a, j);
    ASSERT_LE(exit, w) << "case " << c;
    ASSERT_TRUE(fits(L, v, exit, a, j)) << "case " << c;
    const double above = exit + 1e-6 * v;
    if (above < w) {
      EXPECT_FALSE(fits(L, v, above, a, j)) << "case " << c << ": exit " << exit << " of " << v;
    }
  }
  EXPECT_GT(in_branch, test::random_cases(20000) / 20);  // about 6 % of the cases
}

}  // namespace
}  // namespace stiffpath::motion
