// The metrics of a path separated into sides (SideChain), or of an ordered path cut at its corners (thesis §4.7).
#include "stiffpath/evaluation/path_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/side_chain.hpp"

namespace stiffpath::evaluation {

PathMetrics measure_sides(const std::vector<std::vector<Point2>>& sides, bool closed, const PathMetricsOptions& options) {
  if (sides.empty()) throw Error("path metrics: no sides to measure");
  if (closed && sides.size() < 2) throw Error("path metrics: a closed path needs at least two sides");
  for (std::size_t k = 0; k < sides.size(); ++k) {
    if (sides[k].size() < 2) throw Error(fmt::format("path metrics: side {} has {} point(s), needs two", k + 1, sides[k].size()));
  }
  PathMetrics result;
  result.closed = closed;
  std::vector<std::optional<SideMetrics>> measured(sides.size());
  SideChain chain(
      options, [&](std::size_t k, SideMetrics&& side) { measured[k] = std::move(side); },
      [&](CornerReport&& corner) { result.corners.push_back(corner); });
  for (const auto& side : sides) chain.add(side);
  chain.finish(closed);
  for (auto& side : measured) {
    result.length_m += side->length_m;
    result.deviation_area_m2 += side->deviation_area_m2;
    result.max_deviation_m = std::max(result.max_deviation_m, side->max_deviation_m);
    result.straightness_m = std::max(result.straightness_m, side->straightness_m);
    result.sides.push_back(std::move(*side));
  }
  std::sort(result.corners.begin(), result.corners.end(),
            [](const CornerReport& a, const CornerReport& b) { return a.side_before < b.side_before; });
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
