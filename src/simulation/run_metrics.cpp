// The marked path's metrics from the evaluation module: length, deviation area, max deviation, AT_p, CR, CO.
#include "stiffpath/simulation/run_metrics.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/cornering.hpp"
#include "stiffpath/evaluation/iso9283.hpp"
#include "stiffpath/evaluation/path_metrics.hpp"

namespace stiffpath::simulation {

RunMetrics measure_run(const SimulationResult& run, int sides) {
  if (run.marked.size() < 4 || run.commanded.size() < 2) {
    throw Error(fmt::format("simulation: the laser marked {} points ({} commanded); nothing to measure",
                            run.marked.size(), run.commanded.size()));
  }
  evaluation::PathMetricsOptions options;
  options.closure = sides >= 3 ? evaluation::Closure::closed : evaluation::Closure::open;
  const auto marked = evaluation::measure_path(run.marked, sides, options);
  const auto commanded = evaluation::measure_path(run.commanded, sides, options);
  RunMetrics m;
  m.length_m = marked.length_m;
  m.commanded_length_m = commanded.length_m;
  m.length_error_m = marked.length_m - commanded.length_m;
  m.deviation_area_m2 = marked.deviation_area_m2;
  m.max_deviation_m = marked.max_deviation_m;
  m.path_accuracy_m = evaluation::iso9283_path_accuracy(run.commanded, {run.marked}).accuracy_m;
  for (const auto& corner : evaluation::iso9283_cornering(run.commanded, run.marked)) {
    ++m.corners;
    m.cornering_round_off_m = std::max(m.cornering_round_off_m, corner.round_off_m);
    m.cornering_overshoot_m = std::max(m.cornering_overshoot_m, corner.overshoot_m);
  }
  m.residual_vibration_m = run.residual_vibration_m;
  m.peak_deflection_m = run.peak_deflection_m;
  return m;
}

}  // namespace stiffpath::simulation
