// ISO 9283 cornering round-off CR and overshoot CO: sharp corners of the command, attained points near each.
#include "stiffpath/evaluation/cornering.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/segment_distance.hpp"

namespace stiffpath::evaluation {

namespace {

void require_finite(std::span<const Point2> points, const char* what) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw Error(fmt::format("cornering: {} point {} is not finite ({}, {})", what, i, points[i].x(), points[i].y()));
    }
  }
}

// The corner a run of turning vertices stands for: where the incoming side's line meets the outgoing
// side's; for a (near) reversal, whose lines meet far off or not at all, the vertex furthest along the
// incoming direction.
Point2 ideal_corner(const std::deque<Vertex>& v, std::size_t first, std::size_t last, const Point2& in, const Point2& out,
                    double turn, double min_turn) {
  const double cross = in.x() * out.y() - in.y() * out.x();
  if (turn > std::numbers::pi - min_turn || std::abs(cross) < 1e-6) {
    std::size_t best = first;
    for (std::size_t i = first; i <= last; ++i) best = v[i].point.dot(in) > v[best].point.dot(in) ? i : best;
    return v[best].point;
  }
  // v[first] + s·in = v[last] + u·out, solved for s.
  const Point2 d = v[last].point - v[first].point;
  const double s = (d.x() * out.y() - d.y() * out.x()) / cross;
  return v[first].point + s * in;
}

}  // namespace

CornerFinder::CornerFinder(const CorneringOptions& options) : options_(options), finder_(options.merge_distance_m) {}

void CornerFinder::add(const Point2& p, std::vector<Vertex>& vertices, std::vector<SharpCorner>& corners) {
  const std::size_t from = vertices.size();
  finder_.add(p, vertices);
  take(vertices, from, corners);
}

void CornerFinder::finish(std::vector<Vertex>& vertices, std::vector<SharpCorner>& corners) {
  const std::size_t from = vertices.size();
  finder_.finish(vertices);
  finished_ = true;
  take(vertices, from, corners);
}

void CornerFinder::take(const std::vector<Vertex>& settled, std::size_t from, std::vector<SharpCorner>& corners) {
  for (std::size_t i = from; i < settled.size(); ++i) {
    // A vertex closer than the merge distance to the one before adds no direction (the end of a stop).
    if (!v_.empty() && (settled[i].point - v_.back().point).norm() < options_.merge_distance_m) continue;
    v_.push_back(settled[i]);
  }
  decide(corners);
}

// The batch loop of corner regions, run as far as the vertices known allow: a region may still grow
// while its next vertex could be the command's last.
void CornerFinder::decide(std::vector<SharpCorner>& corners) {
  const double span = options_.max_corner_span_m;
  const auto at = [&](std::size_t k) -> const Vertex& { return v_[k - base_]; };
  for (;;) {
    const std::size_t total = base_ + v_.size();
    if (next_ + 1 >= total) return;  // the candidate is the last vertex known: is it interior?
    const std::size_t first = next_;
    std::size_t last = first;
    for (;;) {
      const bool close = (at(last + 1).point - at(last).point).norm() < span &&
                         (at(last + 1).point - at(first).point).norm() < span;
      if (!close) break;
      if (last + 2 < total) {
        ++last;
        continue;
      }
      if (finished_) break;  // the next vertex is the command's end
      return;                // wait: is the next vertex the end, or interior?
    }
    next_ = last + 1;
    const Point2 a = at(first).point - at(first - 1).point, b = at(last + 1).point - at(last).point;
    const bool straight_sides = a.norm() >= span && b.norm() >= span;
    if (first == last || straight_sides) {
      const Point2 in = a.normalized(), out = b.normalized();
      const double turn = std::atan2(std::abs(in.x() * out.y() - in.y() * out.x()), in.dot(out));
      if (turn > options_.min_turn_rad) {
        SharpCorner c;
        c.at = ideal_corner(v_, first - base_, last - base_, in, out, turn, options_.min_turn_rad);
        c.in = in;
        c.out = out;
        c.turn_rad = turn;
        c.reach_m = options_.neighbourhood_fraction * std::min(a.norm(), b.norm());
        c.first_index = at(first).index;
        c.last_index = at(last).index;
        corners.push_back(c);
      }
    }
    while (base_ + 1 < next_) {  // keep the vertex before the next candidate
      v_.pop_front();
      ++base_;
    }
  }
}

CorneringDeviation corner_deviation(const SharpCorner& corner, const SharpCorner* next, std::span<const Point2> attained,
                                    std::size_t& cursor) {
  const auto inside = [&](std::size_t i) { return (attained[i] - corner.at).norm() < corner.reach_m; };
  const auto in_next = [&](std::size_t i) { return next && (attained[i] - next->at).norm() < next->reach_m; };
  CorneringDeviation d;
  d.corner = corner.at;
  d.turn_rad = corner.turn_rad;
  // The search ends where the path enters the next corner's neighbourhood from outside (it may start
  // inside it: a hatch's next corner lies beside the start of the line before this corner).
  std::size_t first = cursor;
  bool outside_next = false;
  for (; first < attained.size() && !inside(first); ++first) {
    if (!in_next(first)) {
      outside_next = true;
    } else if (outside_next) {
      break;
    }
  }
  if (first == attained.size() || !inside(first)) {  // missed: CR only, from the path searched
    d.reached = false;
    d.round_off_m = std::numeric_limits<double>::infinity();
    const std::size_t stop = std::min(first, attained.size() - 1);
    if (cursor < attained.size()) d.round_off_m = (attained[cursor] - corner.at).norm();
    for (std::size_t i = cursor + 1; i <= stop && i < attained.size(); ++i) {
      d.round_off_m = std::min(d.round_off_m, segment_distance(corner.at, attained[i - 1], attained[i]));
    }
    if (!std::isfinite(d.round_off_m)) {  // nothing left to search: the distance from the path's end
      d.round_off_m = attained.empty() ? 0.0 : (attained.back() - corner.at).norm();
    }
    return d;
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
  return d;
}

std::vector<CorneringDeviation> iso9283_cornering(std::span<const Point2> command, std::span<const Point2> attained,
                                                  const CorneringOptions& options) {
  if (attained.size() < 2) throw Error(fmt::format("cornering: {} attained points; needs two or more", attained.size()));
  if (command.size() < 2) throw Error("cornering: the commanded path needs two distinct points");
  require_finite(command, "commanded");
  require_finite(attained, "attained");
  CornerFinder finder(options);
  std::vector<Vertex> vertices;
  std::vector<SharpCorner> corners;
  for (const auto& p : command) {
    finder.add(p, vertices, corners);
    vertices.clear();
  }
  finder.finish(vertices, corners);
  bool distinct = false;
  for (const auto& p : command) distinct = distinct || (p - command.front()).norm() >= options.merge_distance_m;
  if (!distinct) throw Error("cornering: the commanded path needs two distinct points");
  std::vector<CorneringDeviation> result;
  std::size_t cursor = 0;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    result.push_back(corner_deviation(corners[k], k + 1 < corners.size() ? &corners[k + 1] : nullptr, attained, cursor));
  }
  return result;
}

}  // namespace stiffpath::evaluation
