// Pose accuracy and repeatability from repeated positioning trials: ISO 9283 AP_p and RP_l, the thesis's
// "max diff" (table 3.2), and VDI/DGQ 3441 figures when the points were approached from both sides.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stiffpath/core/data_ref.hpp"

namespace stiffpath::measurement {

//! One positioning trial: the error attained − commanded at a point (SI).
struct PositioningTrial {
  std::string mechanism;        //!< optional column; "" when absent
  std::string point;
  double x_m = 0.0, y_m = 0.0;  //!< commanded position
  int trial = 0;
  int approach = 0;             //!< +1 / −1 for the direction the point was approached from; 0 if not given
  std::optional<double> err_x_m, err_y_m, err_z_m;  //!< missing when the cell is empty
  int line = 0;
};

//! Columns: [mechanism,]point,x_mm,y_mm,trial,[approach,]err_x_mm,err_y_mm[,err_z_mm] (approach: + or -).
//! Empty error cells are missing values (the thesis's table 3.3). Errors name file, line and column for
//! missing columns, wrong units (err_x_in …), non-numbers, NaN and duplicated (mechanism, point,
//! approach, trial).
std::vector<PositioningTrial> load_trials(const core::DataRef& file);
//! The same for a path on disk ("builtin:<path>" for a built-in file).
std::vector<PositioningTrial> load_trials(const std::string& path);
//! The thesis's tables 3.2–3.3, built into the binary (data/thesis/repeatability.csv).
core::DataRef thesis_repeatability();

//! ISO 9283 §7.2–7.3 for one point, over its complete trials (all approaches pooled).
struct PoseStatistics {
  std::string mechanism, point;
  double x_m = 0.0, y_m = 0.0;
  int trials = 0;                       //!< complete trials used (n)
  int missing = 0;                      //!< trials skipped for an empty cell
  double mean_x_m = 0.0, mean_y_m = 0.0, mean_z_m = 0.0;  //!< x̄ − x_c … (AP_x, AP_y, AP_z)
  double ap_m = 0.0;                    //!< AP_p = √(AP_x² + AP_y² + AP_z²)
  double l_mean_m = 0.0;                //!< l̄, mean distance of the attained points to their barycentre
  double s_l_m = 0.0;                   //!< S_l = √(Σ(l_j − l̄)² / (n − 1))
  double rp_m = 0.0;                    //!< RP_l = l̄ + 3·S_l
  double max_diff_x_m = 0.0, max_diff_y_m = 0.0;  //!< max − min of the errors (table 3.2's "Max Diff.")
};

//! VDI/DGQ 3441 for one axis of one point approached from both sides.
struct ReversalPoint {
  std::string point;
  double mean_up_m = 0.0, mean_down_m = 0.0;  //!< x̄↑, x̄↓ (approach + and −)
  double s_up_m = 0.0, s_down_m = 0.0;        //!< sample standard deviations
  double mean_m = 0.0;                        //!< x̄ = (x̄↑ + x̄↓)/2
  double reversal_span_m = 0.0;               //!< U = |x̄↑ − x̄↓|
  double scatter_m = 0.0;                     //!< Ps = 6·(s↑ + s↓)/2
};

//! VDI/DGQ 3441 summary of one axis over all points of a mechanism.
struct Vdi3441Axis {
  std::string mechanism;
  char axis = 'x';
  std::vector<ReversalPoint> points;
  double position_deviation_m = 0.0;  //!< Pa = max x̄ − min x̄
  double reversal_span_max_m = 0.0, reversal_span_mean_m = 0.0;  //!< U_max, Ū
  double scatter_max_m = 0.0, scatter_mean_m = 0.0;              //!< Ps_max, P̄s
  double uncertainty_m = 0.0;  //!< P = max(x̄ + U/2 + Ps/2) − min(x̄ − U/2 − Ps/2)
};

struct RepeatabilityReport {
  std::vector<PoseStatistics> points;     //!< points with ≥ 2 complete trials, in order of appearance
  std::vector<std::string> missing;       //!< "SC x1y1: no complete trial" …
  std::vector<Vdi3441Axis> vdi3441;       //!< only for mechanisms whose every point has ≥ 2 trials per side
};

//! ISO 9283 per point and, where the data are bidirectional, VDI/DGQ 3441 per axis.
RepeatabilityReport analyse_repeatability(const std::vector<PositioningTrial>& trials);

}  // namespace stiffpath::measurement
