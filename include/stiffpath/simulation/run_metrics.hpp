// Metrics of a simulated run on its marked path, computed by the evaluation module (thesis §4.7, ISO 9283).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stiffpath/simulation/simulator.hpp"

namespace stiffpath::simulation {

//! The numbers the thesis read off its laser marks, plus ISO 9283 path accuracy and residual vibration. SI.
struct RunMetrics {
  double length_m = 0.0;             //!< length between start and end of the marked path (sum of sides)
  double commanded_length_m = 0.0;   //!< the same metric on the commanded laser-on path
  double length_error_m = 0.0;       //!< length_m − commanded_length_m
  double deviation_area_m2 = 0.0;    //!< area between the marks' spline and fitted line(s), summed over sides
  double max_deviation_m = 0.0;      //!< largest |spline − line| over the sides
  double path_accuracy_m = 0.0;      //!< ISO 9283 AT_p of the mark against the commanded path (100 normal planes)
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
  //! Why the line metrics were refused (too few points, a side measure_path cannot fit, or a command
  //! more than 50 µm from its own fitted sides: a stroke that is not `sides` straight sides, such as
  //! an arc or a rounded rectangle); empty when `metrics`' line fields are valid.
  std::string refusal;
  bool path_accuracy = false;         //!< whether metrics.path_accuracy_m was measured (a normal plane crossed the mark)
  int sides = 0;                      //!< straight sides the line metrics were measured as (0 when refused)
  RunMetrics metrics;                 //!< this stroke's numbers (residual vibration and peak deflection: 0)
};

//! Measures a simulation stroke by stroke as simulate() hands them over (pass `meter.sink()`), so no
//! whole-job mark is kept: each stroke is measured like measure_run measures a one-stroke job, and the
//! job's totals sum lengths and areas over the strokes and take the largest deviations, AT_p, CR and CO.
//! A one-stroke job gives exactly measure_run's numbers.
class RunMeter {
 public:
  //! `sides`: straight sides of every stroke (1: a line, 3: a triangle), or 0: each stroke's sharp
  //! corners (iso9283_cornering on its command) plus one, closed when the command returns to its
  //! start; `keep_strokes`: how many
  //! StrokeMetrics to keep for strokes() (the totals always cover all).
  explicit RunMeter(int sides, std::size_t keep_strokes = 100000);
  //! Measures one stroke and folds it into the totals.
  void add(const Stroke& stroke);
  //! A sink for simulate() that calls add().
  [[nodiscard]] StrokeSink sink();
  //! The job's totals with `run`'s peaks. Throws stiffpath::Error when no stroke could be measured
  //! at all (the laser marked too little), naming the first stroke's refusal.
  [[nodiscard]] RunMetrics totals(const SimulationResult& run) const;
  [[nodiscard]] const std::vector<StrokeMetrics>& strokes() const noexcept { return kept_; }
  [[nodiscard]] std::size_t stroke_count() const noexcept { return count_; }

 private:
  int sides_;
  std::size_t keep_;
  std::size_t count_ = 0;
  std::string first_refusal_;
  RunMetrics totals_;
  std::vector<StrokeMetrics> kept_;
};

//! Measures `run` as a path of `sides` straight sides (1: a line, 3: the triangle) with
//! evaluation::measure_path, using the interpolating spline (the simulated mark is exact, no scan noise)
//! and the default 1 mm corner trim; AT_p, CR and CO against the commanded laser-on path. Throws stiffpath::Error when the run marked too little.
RunMetrics measure_run(const SimulationResult& run, int sides);

}  // namespace stiffpath::simulation
