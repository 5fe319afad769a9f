// Tests of the online simplification (every point within tolerance, hairpins kept, frontier honest) and resampling.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/vertex_finder.hpp"

namespace stiffpath::evaluation {
namespace {

double segment_distance(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

// Brute force: the distance from p to the polyline through `vertices`.
double polyline_distance(const Point2& p, const std::vector<Point2>& vertices) {
  double best = (vertices.front() - p).norm();
  for (std::size_t i = 1; i < vertices.size(); ++i) best = std::min(best, segment_distance(p, vertices[i - 1], vertices[i]));
  return best;
}

// A wandering path: straight runs, arcs, stops (repeated points), hairpins and noise.
std::vector<Point2> wandering_path(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.3e-6);
  std::vector<Point2> out{{0.0, 0.0}};
  double heading = 0.0;
  for (int piece = 0; piece < 30; ++piece) {
    const double kind = u(rng);
    const int n = 20 + static_cast<int>(u(rng) * 200);
    const double step = 1e-6 + u(rng) * 50e-6;
    if (kind < 0.15) heading += std::numbers::pi;                    // a hairpin
    const double bend = kind > 0.6 ? (u(rng) - 0.5) * 0.05 : 0.0;  // an arc
    for (int i = 0; i < n; ++i) {
      heading += bend;
      const double s = kind > 0.9 && i > n / 2 ? 0.0 : step;  // a stop: the same point again
      out.push_back(out.back() + s * Point2{std::cos(heading), std::sin(heading)} + Point2{noise(rng), noise(rng)});
    }
  }
  return out;
}

TEST(VertexFinder, EveryPointLiesWithinThreeTimesTheToleranceOfTheVertices) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const auto path = wandering_path(seed);
    for (const double tol : {1e-9, 0.1e-6, 1e-6}) {
      VertexFinder finder(tol, 64);
      std::vector<Vertex> vertices;
      for (const auto& p : path) finder.add(p, vertices);
      finder.finish(vertices);
      ASSERT_GE(vertices.size(), 2u);
      EXPECT_EQ(vertices.front().index, 0u);
      EXPECT_EQ(vertices.back().index, path.size() - 1);
      for (std::size_t i = 0; i < vertices.size(); ++i) {
        if (i > 0) EXPECT_LT(vertices[i - 1].index, vertices[i].index);  // in order, each once
        EXPECT_EQ(vertices[i].point, path[vertices[i].index]);          // points of the path
      }
      // Each point against the vertices around it: the segment that spans it in the path's order, and
      // its neighbours (a brute force over the whole polyline would be O(n²)).
      double worst = 0.0;
      std::size_t seg = 0;  // vertices[seg].index <= i < vertices[seg + 1].index
      for (std::size_t i = 0; i < path.size(); ++i) {
        while (seg + 2 < vertices.size() && vertices[seg + 1].index <= i) ++seg;
        std::vector<Point2> around;
        for (std::size_t k = seg == 0 ? 0 : seg - 1; k < std::min(vertices.size(), seg + 3); ++k) around.push_back(vertices[k].point);
        worst = std::max(worst, polyline_distance(path[i], around));
      }
      // The cone keeps points within 2 tol of the chords; moving a vertex to its neighbour at a corner
      // (closer than tol) adds at most one more.
      EXPECT_LE(worst, 3 * tol) << "seed " << seed << " tolerance " << tol;
    }
  }
}

// The far end of a hairpin lies on the ray from its start: a cone alone would not see it turn.
TEST(VertexFinder, KeepsTheApexOfAHairpin) {
  std::vector<Point2> path;
  for (int i = 0; i <= 100; ++i) path.emplace_back(i * 1e-4, 0.0);
  for (int i = 99; i >= 50; --i) path.emplace_back(i * 1e-4, 0.0);
  const auto kept = simplify_path(path, 1e-9);
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_NEAR(kept[1].x(), 0.01, 1e-15);
  EXPECT_NEAR(kept[2].x(), 0.005, 1e-15);
}

// A vertex is never settled below the frontier the finder gave before it.
TEST(VertexFinder, SettlesNoVertexBelowItsFrontier) {
  const auto path = wandering_path(7);
  VertexFinder finder(1e-6, 16);
  std::vector<Vertex> vertices;
  std::size_t frontier = 0;
  for (const auto& p : path) {
    const std::size_t before = vertices.size();
    finder.add(p, vertices);
    for (std::size_t i = before; i < vertices.size(); ++i) EXPECT_GE(vertices[i].index, frontier);
    EXPECT_GE(finder.frontier(), frontier);  // it only moves on
    frontier = finder.frontier();
  }
  const std::size_t before = vertices.size();
  finder.finish(vertices);
  for (std::size_t i = before; i < vertices.size(); ++i) EXPECT_GE(vertices[i].index, frontier);
}

TEST(VertexFinder, RefusesBadInput) {
  EXPECT_THROW(VertexFinder(0.0), Error);
  EXPECT_THROW(VertexFinder(std::nan("")), Error);
  VertexFinder finder(1e-6);
  std::vector<Vertex> out;
  EXPECT_THROW(finder.add({std::nan(""), 0.0}, out), Error);
}

TEST(ResampleAlong, EqualStepsOnThePolylineWithBothEnds) {
  const std::vector<Point2> path{{0, 0}, {0.001, 0}, {0.001, 0.0005}, {0.0013, 0.0009}};
  const double length = 0.001 + 0.0005 + 0.0005;
  const auto samples = resample_along(path, 20e-6);
  ASSERT_EQ(samples.size(), 101u);  // ⌈2 mm / 20 µm⌉ + 1
  EXPECT_EQ(samples.front(), path.front());
  EXPECT_EQ(samples.back(), path.back());
  double total = 0.0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    total += (samples[i] - samples[i - 1]).norm();
    double on = 1.0;
    for (std::size_t k = 1; k < path.size(); ++k) on = std::min(on, segment_distance(samples[i], path[k - 1], path[k]));
    EXPECT_LT(on, 1e-15);
  }
  // Steps along the path of length/100 each (chords across a vertex are shorter: only two corners).
  int full = 0;
  for (std::size_t i = 1; i < samples.size(); ++i) full += std::abs((samples[i] - samples[i - 1]).norm() - length / 100) < 1e-12;
  EXPECT_GE(full, 98);
  EXPECT_NEAR(total, length, 2 * (1 - std::sqrt(0.5)) * length / 100);
  EXPECT_EQ(resample_along(std::vector<Point2>{{1, 2}, {1, 2}}, 1e-5).size(), 1u);  // no length: its point
}

}  // namespace
}  // namespace stiffpath::evaluation
