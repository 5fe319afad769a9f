// The marked path's metrics from the evaluation module, stroke by stroke: length, area, deviation, AT_p, CR, CO.
#include "stiffpath/simulation/run_metrics.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "run_metrics_stroke.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::simulation {

namespace {

// Hands a whole stroke's commands and marks to `meter` in the order simulate() would have.
void replay(detail::StrokeMeter& meter, const std::vector<Vec2>& commanded, const std::vector<Vec2>& marked,
            const std::vector<std::size_t>& first_mark) {
  if (first_mark.size() != commanded.size()) {
    throw Error(fmt::format("simulation: the mark's {} interval starts do not match the {} commanded points (a result "
                            "that kept no mark, or strokes joined without their Stroke::first_mark)",
                            first_mark.size(), commanded.size()));
  }
  for (std::size_t k = 0; k < commanded.size(); ++k) {
    meter.command(commanded[k]);
    const std::size_t to = k + 1 < commanded.size() ? first_mark[k + 1] : marked.size();
    for (std::size_t i = first_mark[k]; i < to && i < marked.size(); ++i) meter.mark(marked[i]);
  }
}

}  // namespace

RunMetrics measure_run(const SimulationResult& run, int sides, const evaluation::PathMetricsOptions& metrics) {
  detail::StrokeMeter meter(sides, metrics);
  replay(meter, run.commanded, run.marked, run.first_mark);
  RunMetrics m = meter.finish(true).metrics;
  m.residual_vibration_m = run.residual_vibration_m;
  m.peak_deflection_m = run.peak_deflection_m;
  return m;
}

RunMeter::RunMeter(int sides, std::size_t keep_strokes, const evaluation::PathMetricsOptions& metrics)
    : sides_(sides), keep_(keep_strokes), metrics_(metrics) {}

RunMeter::~RunMeter() = default;

void RunMeter::begin_stroke(std::size_t index, double t_s) {
  stroke_ = std::make_unique<detail::StrokeMeter>(sides_, metrics_);
  index_ = index;
  start_s_ = t_s;
}

void RunMeter::command(const Vec2& target_m) { stroke_->command(target_m); }

void RunMeter::mark(const Vec2& tip_m) { stroke_->mark(tip_m); }

void RunMeter::end_stroke(double t_s) {
  StrokeMetrics s = stroke_->finish(false);
  stroke_.reset();
  s.index = index_;
  s.start_s = start_s_;
  s.end_s = t_s;
  fold(std::move(s));
}

void RunMeter::add(const Stroke& stroke) {
  begin_stroke(stroke.index, stroke.start_s);
  replay(*stroke_, stroke.commanded, stroke.marked, stroke.first_mark);
  end_stroke(stroke.end_s);
}

void RunMeter::fold(StrokeMetrics s) {
  ++count_;
  if (s.metrics.strokes == 0 && first_refusal_.empty()) {
    first_refusal_ = fmt::format("stroke {} ({:.4f} s to {:.4f} s): {}", s.index + 1, s.start_s, s.end_s, s.refusal);
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
