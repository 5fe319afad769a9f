// Metrics of a simulated run on its marked path, computed by the evaluation module (thesis §4.7, ISO 9283).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/evaluation/path_metrics.hpp"
#include "stiffpath/simulation/simulator.hpp"

namespace stiffpath::simulation {

//! The numbers the thesis read off its laser marks, plus ISO 9283 path accuracy and residual vibration. SI.
struct RunMetrics {
  double length_m = 0.0;             //!< length between start and end of the marked path (sum of sides)
  double commanded_length_m = 0.0;   //!< the same metric on the commanded laser-on path
  double length_error_m = 0.0;       //!< length_m − commanded_length_m
  double deviation_area_m2 = 0.0;    //!< area between the marks' spline and fitted line(s), summed over sides
  double max_deviation_m = 0.0;      //!< largest |spline − line| over the sides
  double path_accuracy_m = 0.0;      //!< ISO 9283 AT_p of the mark against the command, largest over the sides (100 normal planes each)
  std::size_t corners = 0;           //!< sharp corners of the commanded path (0 for a line: the two below are then 0)
  double cornering_round_off_m = 0.0; //!< ISO 9283 CR, largest over the corners
  double cornering_overshoot_m = 0.0; //!< ISO 9283 CO, largest over the corners the mark reached
  double residual_vibration_m = 0.0; //!< max tip deflection after the robot stopped (SimulationResult)
  double peak_deflection_m = 0.0;    //!< max tip deflection during the job
  std::size_t strokes = 0;           //!< laser strokes measured (RunMeter); 1 for measure_run
  //! Strokes whose line metrics (length … max deviation) are in the totals above; the others were
  //! refused (StrokeMetrics::refusal). measure_run throws instead.
  std::size_t line_strokes = 0;
};

//! The metrics of one laser stroke (see Stroke), measured when it ends.
struct StrokeMetrics {
  std::size_t index = 0;              //!< 0-based, in job order
  double start_s = 0.0, end_s = 0.0;  //!< commanded times of its first and last sample
  std::size_t marked_points = 0;
  //! Why the line metrics were refused (too few points, a side that cannot be fitted, another number
  //! of sides than asked for, a command more than 50 µm from its own fitted sides: a stroke that is not
  //! straight sides, such as an arc or a rounded rectangle); empty when `metrics`' line fields are valid.
  std::string refusal;
  bool path_accuracy = false;         //!< whether metrics.path_accuracy_m was measured (a normal plane crossed the mark)
  int sides = 0;                      //!< straight sides the line metrics were measured as (0 when refused)
  RunMetrics metrics;                 //!< this stroke's numbers (residual vibration and peak deflection: 0)
};

namespace detail {
class StrokeMeter;
}

//! Measures a simulation stroke by stroke while it is marked (pass it to simulate() as its
//! StrokeObserver), keeping no stroke whole: time is linear in the job and memory bounded by a few
//! sides (detail::StrokeMeter). Each stroke is cut into sides at its command's sharp corners; each side
//! is measured along its mark (evaluation::SideChain: exactly evaluation::measure_sides' numbers),
//! AT_p per side (100 normal planes), CR and CO per corner. The job's totals sum lengths and areas over
//! the strokes and take the largest deviations, AT_p, CR and CO.
class RunMeter final : public StrokeObserver {
 public:
  //! `sides`: straight sides every stroke must have (1: a line, 3: a triangle; a stroke with another
  //! number of sharp corners gets no line metrics), or 0: each stroke's sharp corners plus one, closed
  //! when the command returns to its start. `keep_strokes`: how many StrokeMetrics to keep for
  //! strokes() (the totals always cover all). `metrics`: the metric options (corner trim …).
  explicit RunMeter(int sides, std::size_t keep_strokes = 100000, const evaluation::PathMetricsOptions& metrics = {});
  ~RunMeter() override;
  RunMeter(const RunMeter&) = delete;
  RunMeter& operator=(const RunMeter&) = delete;

  void begin_stroke(std::size_t index, double t_s) override;
  void command(const Vec2& target_m) override;
  void mark(const Vec2& tip_m) override;
  void end_stroke(double t_s) override;
  //! Measures one whole stroke (as a StrokeSink receives it) and folds it into the totals.
  void add(const Stroke& stroke);
  //! A sink for simulate() that calls add() (strokes are then held whole: prefer passing the meter).
  [[nodiscard]] StrokeSink sink();
  //! The job's totals with `run`'s peaks. Throws stiffpath::Error when no stroke could be measured
  //! at all (the laser marked too little), naming the first stroke's refusal.
  [[nodiscard]] RunMetrics totals(const SimulationResult& run) const;
  [[nodiscard]] const std::vector<StrokeMetrics>& strokes() const noexcept { return kept_; }
  [[nodiscard]] std::size_t stroke_count() const noexcept { return count_; }

 private:
  void fold(StrokeMetrics s);

  int sides_;
  std::size_t keep_;
  evaluation::PathMetricsOptions metrics_;
  std::unique_ptr<detail::StrokeMeter> stroke_;
  std::size_t index_ = 0;
  double start_s_ = 0.0;
  std::size_t count_ = 0;
  std::string first_refusal_;
  RunMetrics totals_;
  std::vector<StrokeMetrics> kept_;
};

//! Measures `run` (a simulate() result that kept its mark) as one stroke, as RunMeter measures a
//! one-stroke job (`sides` as RunMeter's), the residual vibration and peak deflection from `run`.
//! Throws stiffpath::Error when the run marked too little or the stroke is not `sides` straight sides.
RunMetrics measure_run(const SimulationResult& run, int sides, const evaluation::PathMetricsOptions& metrics = {});

}  // namespace stiffpath::simulation
