// Per-side line + spline metrics and corners of a path separated into sides (thesis §4.7).
#include "stiffpath/evaluation/path_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "stiffpath/core/error.hpp"

namespace stiffpath::evaluation {

namespace {

struct Junctions {  // corner before / after each side, when there is one
  std::vector<std::optional<Point2>> before, after;
};

Junctions corners_of(const std::vector<LineFit>& fits, bool closed) {
  const std::size_t n = fits.size();
  Junctions j{std::vector<std::optional<Point2>>(n), std::vector<std::optional<Point2>>(n)};
  const std::size_t count = closed ? n : n - 1;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t next = (k + 1) % n;
    const auto x = intersect(fits[k].line, fits[next].line);
    if (!x) throw Error(fmt::format("path metrics: sides {} and {} are parallel, they have no corner", k + 1, next + 1));
    j.after[k] = *x;
    j.before[next] = *x;
  }
  return j;
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

SideMetrics measure_one(const std::vector<Point2>& all, const std::vector<Point2>& kept, const LineFit& fit,
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
  }
  side.spline = SmoothingSpline::fit(t, u, options.smoothing_cutoff_m);
  const auto [t_min, t_max] = std::minmax_element(t.begin(), t.end());
  side.t_from_m = *t_min;
  side.t_to_m = *t_max;

  // Free ends: the extreme extent of all the side's points along its line (nothing is trimmed there).
  double all_min = std::numeric_limits<double>::infinity(), all_max = -all_min;
  for (const auto& p : all) {
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

PathMetrics measure_sides(const std::vector<std::vector<Point2>>& sides, bool closed, const PathMetricsOptions& options) {
  const std::size_t n = sides.size();
  if (n == 0) throw Error("path metrics: no sides to measure");
  if (closed && n < 2) throw Error("path metrics: a closed path needs at least two sides");
  if (!(options.corner_trim_m >= 0.0) || !std::isfinite(options.corner_trim_m)) {
    throw Error(fmt::format("path metrics: corner trim must be finite and >= 0, got {}", options.corner_trim_m));
  }
  std::vector<LineFit> fits(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (sides[k].size() < 2) throw Error(fmt::format("path metrics: side {} has {} point(s), needs two", k + 1, sides[k].size()));
    fits[k] = fit_line_tls(sides[k]);
  }
  Junctions junctions = corners_of(fits, closed);
  std::vector<std::vector<Point2>> kept(n);
  for (int pass = 0; pass < 2 && n > 1; ++pass) {
    for (std::size_t k = 0; k < n; ++k) {
      kept[k] = trimmed(sides[k], junctions.before[k], junctions.after[k], options.corner_trim_m);
      if (kept[k].size() < 2) {
        throw Error(fmt::format("path metrics: side {} has fewer than two points farther than {} mm from its corners",
                                k + 1, options.corner_trim_m * 1e3));
      }
      const Point2 heading = sides[k].back() - sides[k].front();
      fits[k] = fit_line_tls(kept[k]);
      if (fits[k].line.direction.dot(heading) < 0.0) fits[k].line.direction = -fits[k].line.direction;
    }
    junctions = corners_of(fits, closed);
  }
  if (n == 1) kept[0] = sides[0];

  PathMetrics result;
  result.closed = closed;
  for (std::size_t k = 0; k < n; ++k) {
    SideMetrics side = measure_one(sides[k], kept[k], fits[k], junctions.before[k], junctions.after[k], options);
    if (!(side.length_m > 0.0)) {
      throw Error(fmt::format("path metrics: side {} has non-positive length {} mm (its corners are out of order)",
                              k + 1, side.length_m * 1e3));
    }
    result.length_m += side.length_m;
    result.deviation_area_m2 += side.deviation_area_m2;
    result.max_deviation_m = std::max(result.max_deviation_m, side.max_deviation_m);
    result.straightness_m = std::max(result.straightness_m, side.straightness_m);
    result.sides.push_back(std::move(side));
  }
  const std::size_t corner_count = closed ? n : n - 1;
  for (std::size_t k = 0; k < corner_count; ++k) {
    const std::size_t next = (k + 1) % n;
    CornerReport corner;
    corner.position = *junctions.after[k];
    corner.side_before = k;
    corner.side_after = next;
    corner.angle_rad = angle_between(-fits[k].line.direction, fits[next].line.direction);
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto* pts : {&sides[k], &sides[next]}) {
      for (const auto& p : *pts) nearest = std::min(nearest, (p - corner.position).norm());
    }
    corner.path_distance_m = nearest;
    result.corners.push_back(corner);
  }
  return result;
}

PathMetrics measure_path(std::span<const Point2> points, int n_sides, const PathMetricsOptions& options) {
  if (n_sides < 1) throw Error(fmt::format("path metrics: number of sides must be >= 1, got {}", n_sides));
  if (n_sides == 1 && options.closure != Closure::closed) {
    return measure_sides({std::vector<Point2>(points.begin(), points.end())}, false, options);
  }
  PolylineSplit split = split_polyline(points, n_sides, options);
  return measure_sides(split.sides, split.closed, options);
}

}  // namespace stiffpath::evaluation
