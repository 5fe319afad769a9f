// Online polyline simplification by cone intersection with an RDP choice of the vertex, and arc-length resampling.
#include "stiffpath/evaluation/vertex_finder.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/segment_distance.hpp"

namespace stiffpath::evaluation {

namespace {

// Ramer–Douglas–Peucker over pts[first..last] (exclusive of both ends), appending kept points in order.
void rdp(const std::vector<Vertex>& pts, std::size_t first, std::size_t last, double tol, std::vector<Vertex>& out) {
  if (last <= first + 1) return;
  double worst = 0.0;
  std::size_t at = first;
  for (std::size_t i = first + 1; i < last; ++i) {
    const double d = segment_distance(pts[i].point, pts[first].point, pts[last].point);
    if (d > worst) {
      worst = d;
      at = i;
    }
  }
  if (worst <= tol) return;
  rdp(pts, first, at, tol, out);
  out.push_back(pts[at]);
  rdp(pts, at, last, tol, out);
}

}  // namespace

VertexFinder::VertexFinder(double tolerance_m, std::size_t window) : tol_(tolerance_m), window_(window) {
  if (!(tolerance_m > 0.0) || !std::isfinite(tolerance_m)) {
    throw Error(fmt::format("vertex finder: tolerance must be positive and finite, got {} m", tolerance_m));
  }
  if (window < 2) throw Error("vertex finder: the window must hold at least two points");
}

void VertexFinder::add(const Point2& p, std::vector<Vertex>& out) {
  if (!p.allFinite()) throw Error(fmt::format("vertex finder: point {} is not finite ({}, {})", count_, p.x(), p.y()));
  const Vertex v{count_++, p};
  last_ = v;
  if (!started_) {
    started_ = true;
    anchor_ = v;
    out.push_back(v);
    return;
  }
  consider(v, out);
}

void VertexFinder::consider(const Vertex& v, std::vector<Vertex>& out) {
  const Point2 u = v.point - anchor_.point;
  const double d = u.norm();
  if (d < tol_) return;  // merges into the anchor
  const double w = std::asin(std::min(1.0, tol_ / d));
  if (!cone_) {
    cone_ = true;
    ref_ = u / d;
    lo_ = -w;
    hi_ = w;
    d_max_ = d;
  } else {
    const double phi = std::atan2(ref_.x() * u.y() - ref_.y() * u.x(), ref_.dot(u));
    const double lo = std::max(lo_, phi - w), hi = std::min(hi_, phi + w);
    if (lo > hi || d < d_max_ - tol_) {
      settle(v, out);
      return;
    }
    lo_ = lo;
    hi_ = hi;
    d_max_ = std::max(d_max_, d);
  }
  open_.push_back(v);
  if (open_.size() > window_) open_.pop_front();
}

void VertexFinder::settle(const Vertex& v, std::vector<Vertex>& out) {
  std::size_t best = 0;
  double worst = -1.0;
  for (std::size_t i = 0; i < open_.size(); ++i) {
    const double d = segment_distance(open_[i].point, anchor_.point, v.point);
    if (d > worst) {
      worst = d;
      best = i;
    }
  }
  // The farthest point lies on the outside of the turn; of it and its two neighbours within the
  // tolerance, the vertex is the one nearest the corner where the line from the anchor through the point
  // before meets the line from the point after to `v` (the sample nearest a sharp corner, on whichever
  // side it falls).
  if (best > 0 && best + 1 < open_.size()) {
    const Point2 a = anchor_.point, b = open_[best - 1].point, c = open_[best + 1].point, e = v.point;
    const Point2 in = b - a, leaving = e - c;
    const double cross = in.x() * leaving.y() - in.y() * leaving.x();
    if (in.norm() > 0.0 && leaving.norm() > 0.0 && std::abs(cross) > 1e-3 * in.norm() * leaving.norm()) {
      const Point2 d = c - a;
      const Point2 corner = a + in * ((d.x() * leaving.y() - d.y() * leaving.x()) / cross);
      std::size_t nearest = best;
      for (std::size_t i : {best - 1, best + 1}) {
        const bool near = (open_[i].point - open_[best].point).norm() < tol_;  // keeps every point within 3 tol
        if (near && (open_[i].point - corner).norm() < (open_[nearest].point - corner).norm()) nearest = i;
      }
      best = nearest;
    }
  }
  anchor_ = open_[best];
  out.push_back(anchor_);
  const std::vector<Vertex> rest(open_.begin() + static_cast<std::ptrdiff_t>(best) + 1, open_.end());
  open_.clear();
  cone_ = false;
  for (const auto& q : rest) consider(q, out);
  consider(v, out);
}

void VertexFinder::finish(std::vector<Vertex>& out) {
  if (!started_ || last_.index == anchor_.index) return;
  std::vector<Vertex> pts{anchor_};
  for (const auto& q : open_) {
    if (q.index < last_.index) pts.push_back(q);
  }
  pts.push_back(last_);
  rdp(pts, 0, pts.size() - 1, tol_, out);
  out.push_back(last_);
  anchor_ = last_;
  open_.clear();
  cone_ = false;
}

std::size_t VertexFinder::frontier() const noexcept {
  if (!open_.empty()) return open_.front().index;
  return started_ && last_.index != anchor_.index ? last_.index : count_;
}

std::vector<Point2> simplify_path(std::span<const Point2> points, double tolerance_m) {
  VertexFinder finder(tolerance_m, 64);
  std::vector<Vertex> vertices;
  for (const auto& p : points) finder.add(p, vertices);
  finder.finish(vertices);
  std::vector<Point2> out;
  out.reserve(vertices.size());
  for (const auto& v : vertices) out.push_back(v.point);
  return out;
}

std::vector<Point2> resample_along(std::span<const Point2> points, double step_m) {
  if (!(step_m > 0.0) || !std::isfinite(step_m)) throw Error(fmt::format("resampling step must be positive, got {} m", step_m));
  if (points.empty()) return {};
  double total = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) total += (points[i] - points[i - 1]).norm();
  if (!std::isfinite(total)) throw Error("resampling: a path point is not finite");
  if (!(total > 0.0)) return {points.front()};
  const auto count = static_cast<std::size_t>(std::ceil(total / step_m));
  const double step = total / static_cast<double>(count);
  std::vector<Point2> out;
  out.reserve(count + 1);
  out.push_back(points.front());
  double s0 = 0.0;    // arc length at points[i − 1]
  std::size_t k = 1;  // next sample: arc length k·step
  for (std::size_t i = 1; i < points.size() && k < count; ++i) {
    const Point2 d = points[i] - points[i - 1];
    const double len = d.norm();
    while (len > 0.0 && k < count && static_cast<double>(k) * step <= s0 + len) {
      out.push_back(points[i - 1] + d * ((static_cast<double>(k) * step - s0) / len));
      ++k;
    }
    s0 += len;
  }
  out.push_back(points.back());
  return out;
}

}  // namespace stiffpath::evaluation
