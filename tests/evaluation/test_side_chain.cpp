// Tests of the side-by-side metrics: the windowed chain against the whole-path two-pass computation, along-the-mark weighting, reversals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "stiffpath/evaluation/path_metrics.hpp"
#include "stiffpath/evaluation/side_chain.hpp"
#include "stiffpath/evaluation/vertex_finder.hpp"

namespace stiffpath::evaluation {
namespace {

constexpr double kPi = std::numbers::pi;

struct Direct {
  std::vector<double> length, area, max_deviation;
  std::vector<Point2> corners;
};

// The documented definition computed the plain way, every side at once (no window, no deferral): fit
// every side's arc-length samples, intersect neighbours (free ends at reversals), trim and refit twice.
Direct direct(const std::vector<std::vector<Point2>>& sides, bool closed, const PathMetricsOptions& o) {
  const std::size_t n = sides.size();
  std::vector<std::vector<Point2>> trace(n), samples(n);
  std::vector<Point2> heading(n);
  for (std::size_t k = 0; k < n; ++k) {
    trace[k] = simplify_path(sides[k], o.trace_tolerance_m);
    samples[k] = resample_along(trace[k], o.resample_step_m);
    heading[k] = sides[k].back() - sides[k].front();
  }
  const auto has_next = [&](std::size_t k) { return k + 1 < n || closed; };
  std::vector<LineFit> fit(n);
  for (std::size_t k = 0; k < n; ++k) fit[k] = fit_line_tls(samples[k]);
  std::vector<bool> reversal(n, false);
  for (std::size_t k = 0; k < n; ++k) {
    if (has_next(k)) reversal[k] = angle_between(-fit[k].line.direction, fit[(k + 1) % n].line.direction) < kReversalAngle_rad;
  }
  const auto junctions = [&] {
    std::vector<std::optional<Point2>> after(n);
    for (std::size_t k = 0; k < n; ++k) {
      if (has_next(k) && !reversal[k]) after[k] = intersect(fit[k].line, fit[(k + 1) % n].line);
    }
    return after;
  };
  const auto trimmed = [&](std::size_t k, const std::vector<std::optional<Point2>>& after) {
    const std::optional<Point2> before = k > 0 ? after[k - 1] : closed ? after[n - 1] : std::nullopt;
    std::vector<Point2> kept;
    for (const auto& p : samples[k]) {
      if (before && (p - *before).norm() < o.corner_trim_m) continue;
      if (after[k] && (p - *after[k]).norm() < o.corner_trim_m) continue;
      kept.push_back(p);
    }
    return kept;
  };
  auto after = junctions();
  std::vector<std::vector<Point2>> kept(n);
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t k = 0; k < n; ++k) {
      kept[k] = trimmed(k, after);
      fit[k] = fit_line_tls(kept[k]);
      if (fit[k].line.direction.dot(heading[k]) < 0) fit[k].line.direction = -fit[k].line.direction;
    }
    after = junctions();
  }
  Direct d;
  for (std::size_t k = 0; k < n; ++k) {
    const Line2& line = fit[k].line;
    std::vector<double> t, u;
    for (const auto& p : kept[k]) {
      t.push_back(line.along(p));
      u.push_back(line.offset(p));
    }
    const auto spline = SmoothingSpline::fit(t, u, o.smoothing_cutoff_m);
    const auto [lo, hi] = std::minmax_element(t.begin(), t.end());
    double t_min = 1e300, t_max = -1e300;
    for (const auto& p : trace[k]) {
      t_min = std::min(t_min, line.along(p));
      t_max = std::max(t_max, line.along(p));
    }
    const std::optional<Point2> before = k > 0 ? after[k - 1] : closed ? after[n - 1] : std::nullopt;
    const double t0 = before ? line.along(*before) : t_min, t1 = after[k] ? line.along(*after[k]) : t_max;
    d.length.push_back(t1 - t0);
    d.area.push_back(spline.integral_abs(*lo, *hi));
    d.max_deviation.push_back(spline.extremes(*lo, *hi).max_abs);
    if (after[k]) d.corners.push_back(*after[k]);
  }
  return d;
}

// Points every `step` along a polygon, with noise, one point list per side (sides share their corner).
std::vector<std::vector<Point2>> noisy_sides(const std::vector<Point2>& v, double step, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 2e-6);
  std::vector<std::vector<Point2>> sides;
  for (std::size_t k = 0; k + 1 < v.size(); ++k) {
    const Point2 d = v[k + 1] - v[k];
    const int m = std::max(2, static_cast<int>(std::ceil(d.norm() / step)));
    std::vector<Point2> side;
    for (int i = 0; i <= m; ++i) side.push_back(v[k] + d * (static_cast<double>(i) / m) + Point2{noise(rng), noise(rng)});
    sides.push_back(side);
  }
  return sides;
}

void expect_same(const PathMetrics& chain, const Direct& plain) {
  ASSERT_EQ(chain.sides.size(), plain.length.size());
  for (std::size_t k = 0; k < plain.length.size(); ++k) {
    EXPECT_NEAR(chain.sides[k].length_m, plain.length[k], 1e-13) << "side " << k;
    EXPECT_NEAR(chain.sides[k].deviation_area_m2, plain.area[k], 1e-16) << "side " << k;
    EXPECT_NEAR(chain.sides[k].max_deviation_m, plain.max_deviation[k], 1e-13) << "side " << k;
  }
  ASSERT_EQ(chain.corners.size(), plain.corners.size());
  for (std::size_t k = 0; k < plain.corners.size(); ++k) EXPECT_LT((chain.corners[k].position - plain.corners[k]).norm(), 1e-13);
}

// 40 sides: the chain measures side k when side k + 3 arrives and forgets the sides behind; its numbers
// are the whole-path computation's, open and closed (the first three sides redone with the last).
TEST(SideChain, ALongChainGivesTheWholePathNumbers) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> len(0.004, 0.02), turn(0.5, 2.0);
  std::vector<Point2> v{{0, 0}};
  double heading = 0.0;
  for (int k = 0; k < 40; ++k) {
    v.push_back(v.back() + len(rng) * Point2{std::cos(heading), std::sin(heading)});
    heading += (k % 2 ? -1 : 1) * turn(rng);
  }
  const PathMetricsOptions options;
  const auto open = noisy_sides(v, 30e-6, 1);
  expect_same(measure_sides(open, false, options), direct(open, false, options));
  // A closed polygon: a regular 24-gon of 10 mm sides.
  std::vector<Point2> ring;
  for (int k = 0; k <= 24; ++k) ring.push_back(0.04 * Point2{std::cos(2 * kPi * k / 24), std::sin(2 * kPi * k / 24)});
  const auto closed = noisy_sides(ring, 25e-6, 2);
  const PathMetrics m = measure_sides(closed, true, options);
  expect_same(m, direct(closed, true, options));
  EXPECT_EQ(m.corners.size(), 24u);
  EXPECT_NEAR(m.length_m, 24 * (ring[1] - ring[0]).norm(), 24 * 2e-6);
}

// The definition is along the mark: a path sampled densely where it moves slowly (a move coming to rest
// at both ends, as a simulated mark is sampled in time) measures as the same path sampled evenly. The
// cosine wiggle's closed form: area (2/π)·A·L, max deviation A (interpolating spline).
TEST(SideChain, AMarkSampledInTimeMeasuresAsTheSamePathSampledEvenly) {
  const double amplitude = 50e-6, lambda = 1e-2, length = 0.1;
  const auto at = [&](double x) { return Point2{x, amplitude * std::cos(2 * kPi * x / lambda)}; };
  std::vector<Point2> even, timed;
  for (int i = 0; i <= 20000; ++i) even.push_back(at(-length / 2 + length * i / 20000.0));
  for (int i = 0; i <= 20000; ++i) timed.push_back(at(-length / 2 * std::cos(kPi * i / 20000.0)));  // dense at the ends
  PathMetricsOptions options;
  options.smoothing_cutoff_m = 0.0;
  const PathMetrics a = measure_sides({even}, false, options), b = measure_sides({timed}, false, options);
  EXPECT_NEAR(a.length_m, length, 1e-12);
  EXPECT_NEAR(b.length_m, length, 1e-12);
  EXPECT_NEAR(a.deviation_area_m2, 2 / kPi * amplitude * length, 2e-4 * 2 / kPi * amplitude * length);
  EXPECT_NEAR(b.deviation_area_m2, a.deviation_area_m2, 1e-4 * a.deviation_area_m2);
  EXPECT_NEAR(b.max_deviation_m, a.max_deviation_m, 1e-3 * amplitude);
  // Weighted by time instead (the points as given), the ends' wiggles would count many times over: the
  // raw points' TLS line sits J0(10π)·A ≈ 7 µm off the wiggle's axis, the one along the mark on it.
  const LineFit raw = fit_line_tls(timed);
  EXPECT_GT(std::abs(raw.line.origin.y()), 5e-6);
  EXPECT_LT(std::abs(b.sides[0].fit.line.origin.y()), 0.1e-6);
}

// A hatch's turn: two antiparallel lines 40 µm apart have no corner (their lines meet nowhere near);
// each is measured with free ends, as if alone.
TEST(SideChain, AReversalGivesFreeEndsNotACorner) {
  std::vector<Point2> there, back;
  for (int i = 0; i <= 500; ++i) there.emplace_back(0.01 * i / 500.0, 0.0);
  for (int i = 0; i <= 400; ++i) back.emplace_back(0.01 - 0.008 * i / 400.0, 40e-6 + 1e-9 * i);
  const PathMetrics m = measure_sides({there, back}, false);
  ASSERT_EQ(m.sides.size(), 2u);
  EXPECT_TRUE(m.corners.empty());
  EXPECT_NEAR(m.sides[0].length_m, 0.01, 1e-12);
  EXPECT_NEAR(m.sides[1].length_m, std::hypot(0.008, 400e-9), 1e-12);
  EXPECT_FALSE(m.sides[0].end_is_corner);
  EXPECT_FALSE(m.sides[1].start_is_corner);
  const PathMetrics alone = measure_sides({back}, false);
  EXPECT_EQ(m.sides[1].length_m, alone.sides[0].length_m);
  EXPECT_EQ(m.sides[1].max_deviation_m, alone.sides[0].max_deviation_m);
}

}  // namespace
}  // namespace stiffpath::evaluation
