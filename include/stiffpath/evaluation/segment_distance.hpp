// The distance from a point to a line segment or a polyline: the one measure mark metrics, scans and tests share.
#pragma once

#include <algorithm>
#include <limits>
#include <span>

#include "stiffpath/evaluation/line_fit.hpp"

namespace stiffpath::evaluation {

//! |p − q| for the point q of segment [a, b] nearest p (a, when the segment has no length).
[[nodiscard]] inline double segment_distance(const Point2& p, const Point2& a, const Point2& b) noexcept {
  const Point2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

//! The smallest segment_distance from p to the polyline `path` (to its point when it has one; +∞ when empty).
[[nodiscard]] inline double polyline_distance(const Point2& p, std::span<const Point2> path) noexcept {
  if (path.size() == 1) return (p - path.front()).norm();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < path.size(); ++k) best = std::min(best, segment_distance(p, path[k], path[k + 1]));
  return best;
}

}  // namespace stiffpath::evaluation
