// Tests of the path metrics: lengths, deviation areas against closed forms, corner splitting of random polygons.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/metrics_json.hpp"
#include "stiffpath/evaluation/path_metrics.hpp"

namespace stiffpath::evaluation {
namespace {

constexpr double kPi = std::numbers::pi;

// Points every `step` along the polygon through `vertices` (each vertex included).
std::vector<Point2> densify(const std::vector<Point2>& vertices, double step) {
  std::vector<Point2> out{vertices.front()};
  for (std::size_t k = 0; k + 1 < vertices.size(); ++k) {
    const Point2 d = vertices[k + 1] - vertices[k];
    const int n = std::max(1, static_cast<int>(std::ceil(d.norm() / step)));
    for (int i = 1; i <= n; ++i) out.push_back(vertices[k] + d * (static_cast<double>(i) / n));
  }
  return out;
}

TEST(PathMetrics, StraightRotatedLineHasItsLengthAndNoDeviation) {
  const double angle = 0.05, length = 0.15;
  const Point2 a{0.01, 0.02}, b = a + length * Point2{std::cos(angle), std::sin(angle)};
  const PathMetrics m = measure_path(densify({a, b}, 2e-5), 1);
  ASSERT_EQ(m.sides.size(), 1u);
  EXPECT_NEAR(m.length_m, length, 1e-12);
  EXPECT_LT(m.deviation_area_m2, 1e-18);
  EXPECT_LT(m.max_deviation_m, 1e-13);
  EXPECT_LT((m.sides[0].start - a).norm(), 1e-12);
  EXPECT_LT((m.sides[0].end - b).norm(), 1e-12);
  EXPECT_TRUE(m.corners.empty());
}

TEST(PathMetrics, CosineWiggleHasTheClosedFormAreaAndPeaks) {
  // y = A cos(2πx/λ) on x ∈ [−L/2, L/2], L = 10 λ: the TLS line is y = 0 by symmetry,
  // area = (2/π)·A·L, max deviation A, peak to valley 2A, length L.
  const double amplitude = 5e-5, lambda = 1e-2, length = 0.1;
  std::vector<Point2> pts;
  for (int i = 0; i <= 20000; ++i) {
    const double x = -length / 2 + length * i / 20000.0;
    pts.emplace_back(x, amplitude * std::cos(2 * kPi * x / lambda));
  }
  for (const double cutoff : {0.0, 1e-3}) {
    PathMetricsOptions options;
    options.smoothing_cutoff_m = cutoff;
    const PathMetrics m = measure_path(pts, 1, options);
    const double keep = 1.0 / (1.0 + std::pow(cutoff / lambda, 4));
    EXPECT_NEAR(m.length_m, length, 1e-12);
    EXPECT_NEAR(m.deviation_area_m2, 2 / kPi * amplitude * length * keep, 2e-4 * amplitude * length);
    // The natural end conditions (f'' = 0) let a smoothing spline overshoot a peak that sits at an end by ~1 %.
    const double peak_tol = cutoff > 0 ? 1.5e-2 : 1e-3;
    EXPECT_NEAR(m.max_deviation_m, amplitude * keep, peak_tol * amplitude);
    EXPECT_NEAR(m.straightness_m, 2 * amplitude * keep, 2 * peak_tol * amplitude);
  }
}

TEST(PathMetrics, NoiseIsSmoothedAwayAboveTheCutoffWavelength) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 2e-6);
  std::vector<Point2> pts;
  for (int i = 0; i <= 5000; ++i) pts.emplace_back(0.1 * i / 5000.0, noise(rng));
  const PathMetrics raw = measure_path(pts, 1, PathMetricsOptions{0.0});
  const PathMetrics smooth = measure_path(pts, 1);
  // ≈ E|noise|·L for the interpolating spline, on the arc-length samples: each lies between two noisy points,
  // σ·√(f² + (1 − f)²) at a fraction f between them, on average 0.81 σ, so E|noise| ≈ √(2/π)·0.81·σ.
  EXPECT_GT(raw.deviation_area_m2, 0.1 * 0.8 * 0.81 * 2e-6 * 0.8);
  EXPECT_LT(smooth.deviation_area_m2, raw.deviation_area_m2 / 4);
}

TEST(PathMetrics, TriangleSplitsIntoItsSidesAndCorners) {
  const double side = 0.1;
  const Point2 v0{0.02, 0.03}, v1 = v0 + Point2{side, 0}, v2 = v0 + Point2{side / 2, side * std::sqrt(3) / 2};
  const auto pts = densify({v0, v1, v2, v0}, 5e-5);
  const PathMetrics m = measure_path(pts, 3);
  ASSERT_TRUE(m.closed);
  ASSERT_EQ(m.sides.size(), 3u);
  ASSERT_EQ(m.corners.size(), 3u);
  for (const auto& s : m.sides) {
    EXPECT_NEAR(s.length_m, side, 1e-11);
    EXPECT_LT(s.deviation_area_m2, 1e-16);
  }
  EXPECT_NEAR(m.length_m, 3 * side, 1e-10);
  for (const auto& c : m.corners) {
    EXPECT_NEAR(c.angle_rad, kPi / 3, 1e-9);
    const double to_vertex = std::min({(c.position - v0).norm(), (c.position - v1).norm(), (c.position - v2).norm()});
    EXPECT_LT(to_vertex, 1e-11);
    ASSERT_TRUE(c.path_distance_m.has_value());
    EXPECT_LT(*c.path_distance_m, 1e-11);
  }
}

TEST(PathMetrics, ClosedPathStartingMidSideAndRoundedCorners) {
  // A square starting in the middle of a side, corners cut by 45° chamfers of 0.5 mm legs.
  const double s = 0.05, c = 5e-4;
  const std::vector<Point2> v{{s / 2, 0},     {s - c, 0}, {s, c},     {s, s - c}, {s - c, s}, {c, s},
                              {0, s - c},     {0, c},     {c, 0},     {s / 2, 0}};
  const PathMetrics m = measure_path(densify(v, 2e-5), 4);
  ASSERT_TRUE(m.closed);
  ASSERT_EQ(m.sides.size(), 4u);
  for (const auto& side : m.sides) EXPECT_NEAR(side.length_m, s, 1e-9);
  for (const auto& corner : m.corners) {
    EXPECT_NEAR(corner.angle_rad, kPi / 2, 1e-9);
    EXPECT_NEAR(*corner.path_distance_m, c / std::sqrt(2.0), 1e-6);  // the chamfer's distance from the corner
  }
}

TEST(PathMetrics, RandomOpenPolylinesRecoverTheirCorners) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> len(0.02, 0.08), turn(0.6, 2.3), sign(0, 1);
  std::normal_distribution<double> noise(0.0, 1e-6);
  for (int trial = 0; trial < 40; ++trial) {
    const int sides = 2 + trial % 4;
    std::vector<Point2> v{{0, 0}};
    double heading = sign(rng) * 2 * kPi;
    for (int k = 0; k < sides; ++k) {
      v.push_back(v.back() + len(rng) * Point2{std::cos(heading), std::sin(heading)});
      heading += (sign(rng) < 0.5 ? -1 : 1) * turn(rng);
    }
    auto pts = densify(v, 4e-5);
    for (auto& p : pts) p += Point2{noise(rng), noise(rng)};
    PathMetricsOptions options;
    options.closure = Closure::open;
    const PathMetrics m = measure_path(pts, sides, options);
    ASSERT_EQ(m.sides.size(), static_cast<std::size_t>(sides));
    for (int k = 0; k < sides; ++k) {
      EXPECT_NEAR(m.sides[k].length_m, (v[k + 1] - v[k]).norm(), 5e-6) << "trial " << trial << " side " << k;
    }
    for (int k = 0; k + 1 < sides; ++k) EXPECT_LT((m.corners[k].position - v[k + 1]).norm(), 5e-6);
  }
}

TEST(PathMetrics, JsonCarriesUnitsAndSidesOnlyForSeveralSides) {
  const PathMetrics line = measure_path(densify({{0, 0}, {0.1, 0}}, 1e-4), 1);
  const auto j = to_json(line);
  EXPECT_NEAR(j["length_mm"].get<double>(), 100.0, 1e-9);
  EXPECT_FALSE(j.contains("sides"));
  const PathMetrics tri = measure_path(densify({{0, 0}, {0.03, 0}, {0.015, 0.026}, {0, 0}}, 1e-4), 3);
  const auto t = to_json(tri);
  ASSERT_EQ(t["sides"].size(), 3u);
  ASSERT_EQ(t["corners"].size(), 3u);
  std::vector<double> lengths;
  for (const auto& side : t["sides"]) lengths.push_back(side["length_mm"].get<double>());
  std::sort(lengths.begin(), lengths.end());
  EXPECT_NEAR(lengths[0], 30.0, 1e-6);
  EXPECT_NEAR(lengths[1], std::hypot(15.0, 26.0), 1e-6);  // the two slanted sides
  EXPECT_NEAR(lengths[2], std::hypot(15.0, 26.0), 1e-6);
}

TEST(PathMetrics, JsonNeverCarriesNaN) {
  EXPECT_EQ(round_for_json(0.1234567890123456), 0.123456789012);
  EXPECT_THROW(round_for_json(std::nan("")), std::logic_error);
  EXPECT_THROW(round_for_json(INFINITY), std::logic_error);
}

TEST(PathMetrics, BadInputIsRefused) {
  const std::vector<Point2> two{{0, 0}, {1, 0}};
  EXPECT_THROW(measure_path(two, 0), Error);
  EXPECT_THROW(measure_path(two, 3), Error);
  EXPECT_THROW(measure_sides({two, two}, false), Error);  // parallel consecutive sides have no corner
  EXPECT_THROW(measure_sides({}, false), Error);
}

}  // namespace
}  // namespace stiffpath::evaluation
