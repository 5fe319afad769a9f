// Per-side line + spline metrics and corners (thesis §4.7), side by side with a window of neighbours.
#include "stiffpath/evaluation/side_chain.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/segment_distance.hpp"
#include "stiffpath/evaluation/vertex_finder.hpp"

namespace stiffpath::evaluation {

namespace {

const std::optional<Point2> kNone;  // no junction: a free end

// Distance from p to the polyline through `points` (to its point when it has one).
double polyline_distance(const Point2& p, const std::vector<Point2>& points) {
  double best = points.empty() ? std::numeric_limits<double>::infinity() : (points.front() - p).norm();
  for (std::size_t i = 1; i < points.size(); ++i) best = std::min(best, segment_distance(p, points[i - 1], points[i]));
  return best;
}

std::vector<Point2> trimmed(const std::vector<Point2>& points, const std::optional<Point2>& a,
                            const std::optional<Point2>& b, double trim) {
  std::vector<Point2> kept;
  kept.reserve(points.size());
  for (const auto& p : points) {
    if (a && (p - *a).norm() < trim) continue;
    if (b && (p - *b).norm() < trim) continue;
    kept.push_back(p);
  }
  return kept;
}

// One side's metrics in its fitted line's frame: the spline and area over the kept samples, the free
// ends at the extreme extent of the whole trace along the line.
SideMetrics measure_one(const std::vector<Point2>& trace, const std::vector<Point2>& kept, const LineFit& fit,
                        const std::optional<Point2>& before, const std::optional<Point2>& after,
                        const PathMetricsOptions& options) {
  SideMetrics side;
  side.fit = fit;
  side.point_count = kept.size();
  const Line2& line = fit.line;
  std::vector<double> t(kept.size()), u(kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    t[i] = line.along(kept[i]);
    u[i] = line.offset(kept[i]);
    side.max_offset_m = std::max(side.max_offset_m, std::abs(u[i]));
  }
  side.spline = SmoothingSpline::fit(t, u, options.smoothing_cutoff_m);
  const auto [t_min, t_max] = std::minmax_element(t.begin(), t.end());
  side.t_from_m = *t_min;
  side.t_to_m = *t_max;
  double all_min = std::numeric_limits<double>::infinity(), all_max = -all_min;
  for (const auto& p : trace) {
    all_min = std::min(all_min, line.along(p));
    all_max = std::max(all_max, line.along(p));
  }
  side.start_is_corner = before.has_value();
  side.end_is_corner = after.has_value();
  const double t_start = before ? line.along(*before) : all_min;
  const double t_end = after ? line.along(*after) : all_max;
  side.start = line.at(t_start);
  side.end = line.at(t_end);
  side.length_m = t_end - t_start;
  side.deviation_area_m2 = side.spline.integral_abs(side.t_from_m, side.t_to_m);
  const SplineExtremes ex = side.spline.extremes(side.t_from_m, side.t_to_m);
  side.max_deviation_m = ex.max_abs;
  side.straightness_m = ex.max - ex.min;
  return side;
}

}  // namespace

SideChain::SideChain(const PathMetricsOptions& options, SideSink on_side, CornerSink on_corner)
    : options_(options), on_side_(std::move(on_side)), on_corner_(std::move(on_corner)) {
  if (!(options.corner_trim_m >= 0.0) || !std::isfinite(options.corner_trim_m)) {
    throw Error(fmt::format("path metrics: corner trim must be finite and >= 0, got {}", options.corner_trim_m));
  }
  if (!(options.resample_step_m > 0.0) || !(options.trace_tolerance_m > 0.0) ||
      !std::isfinite(options.resample_step_m + options.trace_tolerance_m)) {
    throw Error(fmt::format("path metrics: resampling step {} m and trace tolerance {} m must be positive",
                            options.resample_step_m, options.trace_tolerance_m));
  }
}

SideChain::Side& SideChain::at(std::size_t k) {
  const auto it = sides_.find(k);
  if (it == sides_.end()) throw std::logic_error(fmt::format("side chain: side {} is no longer held", k + 1));
  return it->second;
}

std::optional<std::size_t> SideChain::prev(std::size_t k) const {
  if (k > 0) return k - 1;
  if (closed_ && finished_) return n_ - 1;
  return std::nullopt;
}

std::optional<std::size_t> SideChain::next(std::size_t k) const {
  if (k + 1 < n_) return k + 1;
  if (closed_ && finished_) return 0;
  return std::nullopt;
}

bool SideChain::reversal_after(std::size_t k) {
  Side& s = at(k);
  if (!s.reversal_after) {
    const auto j = next(k);
    if (!j) throw std::logic_error("side chain: a joint without a next side");
    const double interior = angle_between(-fit(0, k).line.direction, fit(0, *j).line.direction);
    s.reversal_after = interior < kReversalAngle_rad;
    if (*s.reversal_after) ++reversals_;
  }
  return *s.reversal_after;
}

const LineFit& SideChain::fit(int pass, std::size_t k) {
  Side& s = at(k);
  auto& slot = s.fit[static_cast<std::size_t>(pass)];
  if (slot) return *slot;
  if (pass == 0) {
    slot = fit_line_tls(s.samples);
    return *slot;
  }
  const auto p = prev(k);
  const std::optional<Point2>& before = p ? junction(pass - 1, *p) : kNone;
  const std::optional<Point2>& after = junction(pass - 1, k);
  const std::vector<Point2> points = trimmed(s.samples, before, after, options_.corner_trim_m);
  if (points.size() < 2) {
    throw Error(fmt::format("path metrics: side {} has fewer than two points farther than {} mm from its corners", k + 1,
                            options_.corner_trim_m * 1e3));
  }
  LineFit f = fit_line_tls(points);
  if (f.line.direction.dot(s.heading) < 0.0) f.line.direction = -f.line.direction;
  slot = f;
  return *slot;
}

const std::optional<Point2>& SideChain::junction(int pass, std::size_t k) {
  const auto j = next(k);
  if (!j) return kNone;
  auto& slot = at(k).after[static_cast<std::size_t>(pass)];
  if (slot) return *slot;
  if (reversal_after(k)) {
    slot = std::optional<Point2>{};
    return *slot;
  }
  const auto x = intersect(fit(pass, k).line, fit(pass, *j).line);
  if (!x) throw Error(fmt::format("path metrics: sides {} and {} are parallel, they have no corner", k + 1, *j + 1));
  slot = x;
  return *slot;
}

std::vector<Point2> SideChain::kept(std::size_t k) {
  const auto p = prev(k);
  const std::optional<Point2>& before = p ? junction(1, *p) : kNone;
  return trimmed(at(k).samples, before, junction(1, k), options_.corner_trim_m);
}

void SideChain::measure(std::size_t k) {
  Side& s = at(k);
  if (s.measured) return;
  const LineFit& f = fit(2, k);
  const auto p = prev(k);
  const std::optional<Point2>& before = p ? junction(2, *p) : kNone;
  const std::optional<Point2>& after = junction(2, k);
  const std::vector<Point2> points = kept(k);
  if (points.size() < 2) {
    throw Error(fmt::format("path metrics: side {} has fewer than two points farther than {} mm from its corners", k + 1,
                            options_.corner_trim_m * 1e3));
  }
  SideMetrics side = measure_one(s.trace, points, f, before, after, options_);
  if (!(side.length_m > 0.0)) {
    throw Error(fmt::format("path metrics: side {} has non-positive length {} mm (its corners are out of order)", k + 1,
                            side.length_m * 1e3));
  }
  s.measured = true;
  if (on_side_) on_side_(k, std::move(side));
}

void SideChain::report_corner(std::size_t k) {
  const auto j = next(k);
  if (!j) return;
  Side& s = at(k);
  if (s.corner_reported || !s.measured || !at(*j).measured) return;
  s.corner_reported = true;
  if (reversal_after(k)) return;
  CornerReport corner;
  corner.position = *junction(2, k);
  corner.side_before = k;
  corner.side_after = *j;
  corner.angle_rad = angle_between(-fit(2, k).line.direction, fit(2, *j).line.direction);
  corner.path_distance_m = std::min(polyline_distance(corner.position, s.trace), polyline_distance(corner.position, at(*j).trace));
  if (on_corner_) on_corner_(std::move(corner));
}

// Drops what no later side needs: the points of a measured side once both its corners are reported,
// and whole sides eight behind. The first four stay (the first three are measured at finish(), with the
// fourth's numbers and points).
void SideChain::forget_before(std::size_t k) {
  for (auto it = sides_.begin(); it != sides_.end();) {
    const std::size_t i = it->first;
    Side& s = it->second;
    const auto before = sides_.find(i - 1);  // not held any more: it was done
    const bool done = s.measured && s.corner_reported && i >= 4 && i < k &&
                      (before == sides_.end() || before->second.corner_reported);
    if (done && i + 8 < k) {
      it = sides_.erase(it);
      continue;
    }
    if (done) {
      s.trace = {};
      s.samples = {};
    }
    ++it;
  }
}

void SideChain::add(std::span<const Point2> points) {
  if (points.size() < 2) throw Error(fmt::format("path metrics: side {} has {} point(s), needs two", n_ + 1, points.size()));
  add_trace(simplify_path(points, options_.trace_tolerance_m));
}

void SideChain::add_trace(std::vector<Point2> trace) {
  if (finished_) throw std::logic_error("side chain: add() after finish()");
  if (trace.size() < 2) throw Error(fmt::format("path metrics: side {} has {} point(s), needs two", n_ + 1, trace.size()));
  Side s;
  s.samples = resample_along(trace, options_.resample_step_m);
  if (s.samples.size() < 2) throw Error(fmt::format("path metrics: side {} has no length", n_ + 1));
  s.heading = trace.back() - trace.front();
  s.trace = std::move(trace);
  sides_.emplace(n_, std::move(s));
  ++n_;
  // Side k's numbers are final once side k + 3 is known; the first three wait for finish().
  if (n_ >= 7) {
    const std::size_t k = n_ - 4;
    measure(k);
    report_corner(k - 1);
    forget_before(k);
  }
}

void SideChain::finish(bool closed) {
  if (finished_) throw std::logic_error("side chain: finish() twice");
  if (n_ == 0) throw Error("path metrics: no sides to measure");
  if (closed && n_ < 2) throw Error("path metrics: a closed path needs at least two sides");
  finished_ = true;
  closed_ = closed;
  if (closed) {
    // The joint between the last and the first side now exists: what depends on it is worked out again
    // (its reach: fits of the two sides after one pass, of four after two, junctions of five).
    const auto n = static_cast<std::ptrdiff_t>(n_);
    const auto wrap = [n](std::ptrdiff_t d) { return static_cast<std::size_t>(((d % n) + n) % n); };
    for (std::ptrdiff_t d : {-1, 0}) at(wrap(d)).fit[1].reset();
    for (std::ptrdiff_t d : {-2, -1, 0, 1}) at(wrap(d)).fit[2].reset();
    for (std::ptrdiff_t d : {-2, -1, 0}) at(wrap(d)).after[1].reset();
    for (std::ptrdiff_t d : {-3, -2, -1, 0, 1}) at(wrap(d)).after[2].reset();
  }
  for (auto& [k, s] : sides_) {
    if (!s.measured) measure(k);
  }
  for (auto& [k, s] : sides_) report_corner(k);
}

}  // namespace stiffpath::evaluation
