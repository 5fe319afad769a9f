// The distance from a point to a line segment: the one measure the mark metrics' corner and side code share.
#pragma once

#include <algorithm>

#include "stiffpath/evaluation/line_fit.hpp"

namespace stiffpath::evaluation {

//! |p − q| for the point q of segment [a, b] nearest p (a, when the segment has no length).
[[nodiscard]] inline double segment_distance(const Point2& p, const Point2& a, const Point2& b) noexcept {
  const Point2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

}  // namespace stiffpath::evaluation
