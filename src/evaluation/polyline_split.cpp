// Cutting an ordered path into straight sides at its corners (greedy farthest-point split, then line refinement).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <queue>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/path_metrics.hpp"

namespace stiffpath::evaluation {

namespace {

// Distance from p to the chord a–b (to the point a when the chord is degenerate, as in a closed loop).
double chord_distance(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const double len = ab.norm();
  if (len < 1e-12) return (p - a).norm();
  return std::abs(ab.x() * (p.y() - a.y()) - ab.y() * (p.x() - a.x())) / len;
}

// Greedy Ramer–Douglas–Peucker: split the piece holding the farthest point until there are n pieces.
// Each piece's farthest point is found once, when the piece is made, and the pieces wait in a heap:
// O(n log n) for balanced splits instead of a rescan of every piece per break.
std::vector<std::size_t> greedy_breaks(const std::vector<Point2>& q, int n) {
  struct Piece {
    double distance;  // of its farthest interior point from its chord; −1 without interior points
    std::size_t index, first, last;
  };
  const auto farthest = [&](std::size_t a, std::size_t b) {
    Piece piece{-1.0, 0, a, b};
    for (std::size_t i = a + 1; i < b; ++i) {
      const double d = chord_distance(q[i], q[a], q[b]);
      if (d > piece.distance) {
        piece.distance = d;
        piece.index = i;
      }
    }
    return piece;
  };
  // The farthest point first; of equal ones, the one earliest along the path.
  const auto later = [](const Piece& x, const Piece& y) {
    return x.distance < y.distance || (x.distance == y.distance && x.index > y.index);
  };
  std::priority_queue<Piece, std::vector<Piece>, decltype(later)> heap(later);
  heap.push(farthest(0, q.size() - 1));
  std::vector<std::size_t> breaks{0, q.size() - 1};
  while (static_cast<int>(breaks.size()) - 1 < n) {
    const Piece top = heap.top();
    if (top.distance < 0.0) throw Error(fmt::format("path split: {} points are too few for {} sides", q.size(), n));
    heap.pop();
    breaks.push_back(top.index);
    heap.push(farthest(top.first, top.index));
    heap.push(farthest(top.index, top.last));
  }
  std::sort(breaks.begin(), breaks.end());
  return breaks;
}

// Fit of the points of piece [a, b] farther than `trim` from both of its ends.
std::optional<LineFit> piece_fit(const std::vector<Point2>& q, std::size_t a, std::size_t b, double trim) {
  std::vector<Point2> pts;
  for (std::size_t i = a; i <= b; ++i) {
    if ((q[i] - q[a]).norm() >= trim && (q[i] - q[b]).norm() >= trim) pts.push_back(q[i]);
  }
  if (pts.size() < 2) {
    pts.assign(q.begin() + static_cast<std::ptrdiff_t>(a), q.begin() + static_cast<std::ptrdiff_t>(b) + 1);
  }
  if (pts.size() < 2) return std::nullopt;
  return fit_line_tls(pts);
}

// Moves each interior break to the path point nearest the intersection of its neighbours' lines.
void refine_breaks(const std::vector<Point2>& q, std::vector<std::size_t>& breaks, double trim) {
  for (int pass = 0; pass < 3; ++pass) {
    for (std::size_t k = 1; k + 1 < breaks.size(); ++k) {
      const auto before = piece_fit(q, breaks[k - 1], breaks[k], trim);
      const auto after = piece_fit(q, breaks[k], breaks[k + 1], trim);
      if (!before || !after) continue;
      const auto x = intersect(before->line, after->line);
      if (!x) continue;
      std::size_t best = breaks[k];
      double best_d = std::numeric_limits<double>::infinity();
      for (std::size_t i = breaks[k - 1] + 1; i < breaks[k + 1]; ++i) {
        const double d = (q[i] - *x).norm();
        if (d < best_d) {
          best_d = d;
          best = i;
        }
      }
      breaks[k] = best;
    }
  }
}

std::vector<Point2> rotated_loop(std::span<const Point2> points, std::size_t start) {
  std::vector<Point2> q(points.begin() + static_cast<std::ptrdiff_t>(start), points.end());
  q.insert(q.end(), points.begin(), points.begin() + static_cast<std::ptrdiff_t>(start) + 1);
  return q;
}

}  // namespace

PolylineSplit split_polyline(std::span<const Point2> points, int n_sides, const PathMetricsOptions& options) {
  if (n_sides < 1) throw Error(fmt::format("path split: number of sides must be >= 1, got {}", n_sides));
  if (points.size() < static_cast<std::size_t>(n_sides) + 1) {
    throw Error(fmt::format("path split: {} points are too few for {} sides", points.size(), n_sides));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw Error(fmt::format("path split: point {} is not finite", i));
  }
  double path_length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) path_length += (points[i] - points[i - 1]).norm();
  const double gap = (points.back() - points.front()).norm();
  PolylineSplit split;
  split.closed = options.closure == Closure::closed ||
                 (options.closure == Closure::automatic && n_sides >= 3 &&
                  gap < options.closed_gap_fraction * path_length / n_sides);
  if (split.closed && n_sides < 2) throw Error("path split: a closed path needs at least two sides");

  std::vector<Point2> q(points.begin(), points.end());
  std::vector<std::size_t> breaks;
  if (split.closed) {
    // Start at the point farthest from the centroid (a corner of the loop), split, then restart at the
    // path point nearest the refined corner between the last and the first side.
    Point2 centroid{0.0, 0.0};
    for (const auto& p : points) centroid += p;
    centroid /= static_cast<double>(points.size());
    std::size_t start = 0;
    for (std::size_t i = 1; i < points.size(); ++i) {
      if ((points[i] - centroid).norm() > (points[start] - centroid).norm()) start = i;
    }
    for (int pass = 0; pass < 2; ++pass) {
      q = rotated_loop(points, start);
      breaks = greedy_breaks(q, n_sides);
      refine_breaks(q, breaks, options.corner_trim_m);
      if (pass == 1) break;
      const auto first = piece_fit(q, breaks[0], breaks[1], options.corner_trim_m);
      const auto last = piece_fit(q, breaks[breaks.size() - 2], breaks.back(), options.corner_trim_m);
      const auto x = first && last ? intersect(last->line, first->line) : std::nullopt;
      if (!x) break;
      std::size_t nearest = start;
      for (std::size_t i = 0; i < points.size(); ++i) {
        if ((points[i] - *x).norm() < (points[nearest] - *x).norm()) nearest = i;
      }
      start = nearest;
    }
  } else {
    breaks = greedy_breaks(q, n_sides);
    refine_breaks(q, breaks, options.corner_trim_m);
  }
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    split.sides.emplace_back(q.begin() + static_cast<std::ptrdiff_t>(breaks[k]),
                             q.begin() + static_cast<std::ptrdiff_t>(breaks[k + 1]) + 1);
  }
  return split;
}

}  // namespace stiffpath::evaluation
