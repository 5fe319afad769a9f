// The marked path's metrics from the evaluation module: length, deviation area, max deviation, AT_p, CR, CO.
#include "stiffpath/simulation/run_metrics.hpp"

#include <algorithm>
#include <span>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/cornering.hpp"
#include "stiffpath/evaluation/iso9283.hpp"
#include "stiffpath/evaluation/path_metrics.hpp"

namespace stiffpath::simulation {

namespace {

// A command whose ends are closer than this is a closed path (m).
constexpr double kClosedGap_m = 1e-6;

// Fewer points than this in the mark (or two in the command) leave nothing to measure.
std::string too_short(std::size_t marked, std::size_t commanded) {
  if (marked >= 4 && commanded >= 2) return {};
  return fmt::format("the laser marked {} points ({} commanded); nothing to measure", marked, commanded);
}

// One stroke's line metrics, AT_p and cornering. The line metrics are refused (an error message) rather
// than thrown when the stroke is not `sides` straight sides; `strict` throws instead (measure_run).
StrokeMetrics measure_stroke(std::span<const Vec2> marked, std::span<const Vec2> commanded, int sides, bool strict) {
  StrokeMetrics s;
  s.marked_points = marked.size();
  s.refusal = too_short(marked.size(), commanded.size());
  if (!s.refusal.empty()) {
    if (strict) throw Error("simulation: " + s.refusal);
    return s;
  }
  RunMetrics& m = s.metrics;
  try {
    for (const auto& corner : evaluation::iso9283_cornering(commanded, marked)) {
      ++m.corners;
      m.cornering_round_off_m = std::max(m.cornering_round_off_m, corner.round_off_m);
      m.cornering_overshoot_m = std::max(m.cornering_overshoot_m, corner.overshoot_m);
    }
  } catch (const Error&) {
    if (strict) throw;
  }
  // sides 0: as many straight sides as the command has sharp corners plus one, closed when the
  // command ends where it started (a triangle: two interior corners, three sides).
  const bool closes = (commanded.back() - commanded.front()).norm() < kClosedGap_m;
  const int n_sides = sides > 0 ? sides : static_cast<int>(m.corners) + 1;
  evaluation::PathMetricsOptions options;
  options.closure = (sides > 0 ? sides >= 3 : closes && n_sides >= 3) ? evaluation::Closure::closed
                                                                       : evaluation::Closure::open;
  try {
    const auto mark = evaluation::measure_path(marked, n_sides, options);
    const auto command = evaluation::measure_path(commanded, n_sides, options);
    m.length_m = mark.length_m;
    m.commanded_length_m = command.length_m;
    m.length_error_m = mark.length_m - command.length_m;
    m.deviation_area_m2 = mark.deviation_area_m2;
    m.max_deviation_m = mark.max_deviation_m;
    m.line_strokes = 1;
    s.sides = n_sides;
  } catch (const Error& e) {
    if (strict) throw;
    s.refusal = fmt::format("not {} straight side{}: {}", n_sides, n_sides == 1 ? "" : "s", e.what());
  }
  const std::vector<Vec2> mark(marked.begin(), marked.end());
  try {
    m.path_accuracy_m = evaluation::iso9283_path_accuracy(commanded, {mark}).accuracy_m;
    s.path_accuracy = true;
  } catch (const Error&) {
    if (strict) throw;
  }
  m.strokes = 1;
  return s;
}

}  // namespace

RunMetrics measure_run(const SimulationResult& run, int sides) {
  RunMetrics m = measure_stroke(run.marked, run.commanded, sides, true).metrics;
  m.residual_vibration_m = run.residual_vibration_m;
  m.peak_deflection_m = run.peak_deflection_m;
  return m;
}

RunMeter::RunMeter(int sides, std::size_t keep_strokes) : sides_(sides), keep_(keep_strokes) {}

void RunMeter::add(const Stroke& stroke) {
  StrokeMetrics s = measure_stroke(stroke.marked, stroke.commanded, sides_, false);
  s.index = stroke.index;
  s.start_s = stroke.start_s;
  s.end_s = stroke.end_s;
  ++count_;
  if (s.metrics.strokes == 0 && first_refusal_.empty()) {
    first_refusal_ = fmt::format("stroke {} ({:.4f} s to {:.4f} s): {}", stroke.index + 1, s.start_s, s.end_s, s.refusal);
  }
  const RunMetrics& m = s.metrics;
  RunMetrics& t = totals_;
  t.strokes += m.strokes;
  if (m.line_strokes > 0) {
    t.length_m += m.length_m;
    t.commanded_length_m += m.commanded_length_m;
    t.length_error_m += m.length_error_m;
    t.deviation_area_m2 += m.deviation_area_m2;
    t.max_deviation_m = std::max(t.max_deviation_m, m.max_deviation_m);
    ++t.line_strokes;
  }
  t.path_accuracy_m = std::max(t.path_accuracy_m, m.path_accuracy_m);
  t.corners += m.corners;
  t.cornering_round_off_m = std::max(t.cornering_round_off_m, m.cornering_round_off_m);
  t.cornering_overshoot_m = std::max(t.cornering_overshoot_m, m.cornering_overshoot_m);
  if (kept_.size() < keep_) kept_.push_back(std::move(s));
}

StrokeSink RunMeter::sink() {
  return [this](const Stroke& stroke) { add(stroke); };
}

RunMetrics RunMeter::totals(const SimulationResult& run) const {
  if (totals_.strokes == 0) {
    throw Error(count_ == 0 ? std::string("simulation: the laser never fired; nothing to measure")
                            : "simulation: " + first_refusal_);
  }
  RunMetrics m = totals_;
  m.residual_vibration_m = run.residual_vibration_m;
  m.peak_deflection_m = run.peak_deflection_m;
  return m;
}

}  // namespace stiffpath::simulation
