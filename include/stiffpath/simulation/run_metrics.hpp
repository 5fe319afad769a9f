// Metrics of a simulated run on its marked path, computed by the evaluation module (thesis §4.7, ISO 9283).
#pragma once

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
};

//! Measures `run` as a path of `sides` straight sides (1: a line, 3: the triangle) with
//! evaluation::measure_path, using the interpolating spline (the simulated mark is exact, no scan noise)
//! and the default 1 mm corner trim; AT_p, CR and CO against the commanded laser-on path. Throws stiffpath::Error when the run marked too little.
RunMetrics measure_run(const SimulationResult& run, int sides);

}  // namespace stiffpath::simulation
