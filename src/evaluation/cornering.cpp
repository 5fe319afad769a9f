// ISO 9283 cornering round-off CR and overshoot CO: sharp corners of the command, attained points near each.
#include "stiffpath/evaluation/cornering.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::evaluation {

namespace {

double segment_distance(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

void require_finite(std::span<const Point2> points, const char* what) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw Error(fmt::format("cornering: {} point {} is not finite ({}, {})", what, i, points[i].x(), points[i].y()));
    }
  }
}

// Ramer–Douglas–Peucker: the indices of the points that a polyline within `tolerance` needs.
std::vector<std::size_t> simplify(std::span<const Point2> points, double tolerance) {
  std::vector<char> keep(points.size(), 0);
  keep.front() = keep.back() = 1;
  std::vector<std::pair<std::size_t, std::size_t>> stack{{0, points.size() - 1}};
  while (!stack.empty()) {
    const auto [first, last] = stack.back();
    stack.pop_back();
    double worst = 0.0;
    std::size_t worst_index = first;
    for (std::size_t i = first + 1; i < last; ++i) {
      const double d = segment_distance(points[i], points[first], points[last]);
      if (d > worst) {
        worst = d;
        worst_index = i;
      }
    }
    if (worst > tolerance) {
      keep[worst_index] = 1;
      stack.emplace_back(first, worst_index);
      stack.emplace_back(worst_index, last);
    }
  }
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (keep[i] && (kept.empty() || (points[i] - points[kept.back()]).norm() >= tolerance)) kept.push_back(i);
  }
  return kept;
}

struct Corner {
  Point2 at, in, out;  // corner point, unit incoming and outgoing directions
  double turn_rad = 0.0;
  double reach_m = 0.0;  // half the shorter adjacent side (neighbourhood radius)
};

// The corner a run of turning vertices stands for: where the incoming side's line meets the outgoing
// side's (for a reversal, the vertex furthest along the incoming direction).
Point2 ideal_corner(const std::vector<Point2>& v, std::size_t first, std::size_t last, const Point2& in,
                    const Point2& out) {
  const double cross = in.x() * out.y() - in.y() * out.x();
  if (std::abs(cross) < 1e-6) {
    std::size_t best = first;
    for (std::size_t i = first; i <= last; ++i) best = v[i].dot(in) > v[best].dot(in) ? i : best;
    return v[best];
  }
  // v[first] + s·in = v[last] + u·out, solved for s.
  const Point2 d = v[last] - v[first];
  const double s = (d.x() * out.y() - d.y() * out.x()) / cross;
  return v[first] + s * in;
}

std::vector<Corner> find_corners(std::span<const Point2> command, const CorneringOptions& options) {
  const auto kept = simplify(command, options.merge_distance_m);
  std::vector<Point2> v;
  for (auto i : kept) v.push_back(command[i]);
  if (v.size() < 2) throw Error("cornering: the commanded path needs two distinct points");
  std::vector<Corner> corners;
  // Vertices joined by segments shorter than the corner span form one corner region (a corner that a
  // smoothed or blended command rounds over a few µm); the region is a corner when straight sides at
  // least that long enter and leave it and they turn by more than min_turn_rad. A region the span ends
  // before a long side does (a fillet, an arc) is no corner.
  const double span = options.max_corner_span_m;
  std::size_t i = 1;
  while (i + 1 < v.size()) {
    const std::size_t first = i;
    std::size_t last = i;
    while (last + 2 < v.size() && (v[last + 1] - v[last]).norm() < span && (v[last + 1] - v[first]).norm() < span) ++last;
    i = last + 1;
    const Point2 a = v[first] - v[first - 1], b = v[last + 1] - v[last];
    if (first != last && !(a.norm() >= span && b.norm() >= span)) continue;
    const Point2 in = a.normalized(), out = b.normalized();
    const double turn = std::atan2(std::abs(in.x() * out.y() - in.y() * out.x()), in.dot(out));
    if (turn <= options.min_turn_rad) continue;
    corners.push_back({ideal_corner(v, first, last, in, out), in, out, turn,
                       options.neighbourhood_fraction * std::min(a.norm(), b.norm())});
  }
  return corners;
}

}  // namespace

std::vector<CorneringDeviation> iso9283_cornering(std::span<const Point2> command, std::span<const Point2> attained,
                                                  const CorneringOptions& options) {
  if (attained.size() < 2) throw Error(fmt::format("cornering: {} attained points; needs two or more", attained.size()));
  if (command.size() < 2) throw Error("cornering: the commanded path needs two distinct points");
  require_finite(command, "commanded");
  require_finite(attained, "attained");
  std::vector<CorneringDeviation> result;
  std::size_t cursor = 0;
  for (const auto& corner : find_corners(command, options)) {
    const auto inside = [&](std::size_t i) { return (attained[i] - corner.at).norm() < corner.reach_m; };
    CorneringDeviation d;
    d.corner = corner.at;
    d.turn_rad = corner.turn_rad;
    std::size_t first = cursor;
    while (first < attained.size() && !inside(first)) ++first;
    if (first == attained.size()) {  // missed by more than the neighbourhood: CR only, from the whole path
      d.reached = false;
      d.round_off_m = (attained[0] - corner.at).norm();
      for (std::size_t i = 1; i < attained.size(); ++i) {
        d.round_off_m = std::min(d.round_off_m, segment_distance(corner.at, attained[i - 1], attained[i]));
      }
      result.push_back(d);
      continue;
    }
    std::size_t last = first;
    while (last + 1 < attained.size() && inside(last + 1)) ++last;
    cursor = last + 1;
    // Inertia carries the tool on along the incoming direction: the outside of the outgoing side is
    // the incoming direction's part normal to it (a reversal overshoots along the incoming direction).
    Point2 outside = corner.in - corner.in.dot(corner.out) * corner.out;
    outside = outside.norm() > 1e-6 ? Point2(outside.normalized()) : corner.in;
    d.round_off_m = (attained[first] - corner.at).norm();
    for (std::size_t i = first; i <= last; ++i) {
      if (i > first) d.round_off_m = std::min(d.round_off_m, segment_distance(corner.at, attained[i - 1], attained[i]));
      d.overshoot_m = std::max(d.overshoot_m, (attained[i] - corner.at).dot(outside));
    }
    result.push_back(d);
  }
  return result;
}

}  // namespace stiffpath::evaluation
