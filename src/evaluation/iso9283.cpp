// ISO 9283 path accuracy: crossings of attained paths with normal lines of the commanded path, barycentres, maxima.
#include "stiffpath/evaluation/iso9283.hpp"

#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>

#include "stiffpath/core/error.hpp"

namespace stiffpath::evaluation {

namespace {

// The crossing of the polyline `run` with the line through c normal to `tangent`, nearest to c.
std::optional<Point2> nearest_crossing(const std::vector<Point2>& run, const Point2& c, const Point2& tangent) {
  std::optional<Point2> best;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < run.size(); ++i) {
    const double fa = (run[i] - c).dot(tangent), fb = (run[i + 1] - c).dot(tangent);
    if ((fa > 0.0 && fb > 0.0) || (fa < 0.0 && fb < 0.0) || fa == fb) continue;
    const Point2 x = run[i] + (fa / (fa - fb)) * (run[i + 1] - run[i]);
    const double d = (x - c).norm();
    if (d < best_d) {
      best_d = d;
      best = x;
    }
  }
  return best;
}

}  // namespace

PathAccuracy iso9283_path_accuracy(std::span<const Point2> command, const std::vector<std::vector<Point2>>& runs,
                                   std::size_t planes) {
  if (runs.empty()) throw Error("path accuracy: no attained paths given");
  if (planes == 0) throw Error("path accuracy: needs at least one normal plane");
  std::vector<double> cumulative{0.0};
  for (std::size_t i = 1; i < command.size(); ++i) cumulative.push_back(cumulative.back() + (command[i] - command[i - 1]).norm());
  const double total = cumulative.back();
  if (command.size() < 2 || !(total > 0.0) || !std::isfinite(total)) {
    throw Error("path accuracy: the commanded path needs two distinct finite points");
  }
  PathAccuracy result;
  result.planes_requested = planes;
  std::size_t segment = 0;
  for (std::size_t i = 0; i < planes; ++i) {
    const double s = total * (static_cast<double>(i) + 0.5) / static_cast<double>(planes);
    while (segment + 2 < command.size() && cumulative[segment + 1] < s) ++segment;
    const Point2 d = command[segment + 1] - command[segment];
    const double len = d.norm();
    if (len <= 0.0) continue;
    const Point2 tangent = d / len;
    const Point2 c = command[segment] + (s - cumulative[segment]) * tangent;
    std::vector<Point2> crossings;
    for (const auto& run : runs) {
      const auto x = nearest_crossing(run, c, tangent);
      if (!x) break;
      crossings.push_back(*x);
    }
    if (crossings.size() != runs.size()) continue;
    Point2 bary{0.0, 0.0};
    for (const auto& x : crossings) bary += x;
    bary /= static_cast<double>(crossings.size());
    const double deviation = (bary - c).norm();
    result.accuracy_m = std::max(result.accuracy_m, deviation);
    if (crossings.size() > 1) {
      double mean = 0.0, sq = 0.0;
      for (const auto& x : crossings) mean += (x - bary).norm();
      mean /= static_cast<double>(crossings.size());
      for (const auto& x : crossings) sq += std::pow((x - bary).norm() - mean, 2);
      const double sd = std::sqrt(sq / static_cast<double>(crossings.size() - 1));
      result.repeatability_m = std::max(result.repeatability_m, mean + 3.0 * sd);
    }
    result.arc_length_m.push_back(s);
    result.deviation_m.push_back(deviation);
    ++result.planes_used;
  }
  if (result.planes_used == 0) {
    throw Error(fmt::format("path accuracy: none of the {} normal planes crosses every attained path", planes));
  }
  return result;
}

}  // namespace stiffpath::evaluation
