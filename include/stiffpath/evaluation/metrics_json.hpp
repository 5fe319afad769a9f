// JSON form of path metrics with units in the keys (mm, mm², deg), shared by `scan`, `render-scan` and the simulator.
#pragma once

#include <nlohmann/json.hpp>

#include "stiffpath/evaluation/path_metrics.hpp"

namespace stiffpath::evaluation {

//! {length_mm, deviation_area_mm2, max_deviation_mm, straightness_mm, closed, and for more than one
//! side: sides [{length_mm, deviation_area_mm2, max_deviation_mm, straightness_mm, direction_deg,
//! start_mm [x, y], end_mm [x, y], rms_residual_mm, points}], corners [{x_mm, y_mm, angle_deg,
//! path_distance_mm?}]}. Numbers are rounded to 12 significant digits; no NaN can appear.
nlohmann::json to_json(const PathMetrics& metrics);

//! One side as in the `sides` array above.
nlohmann::json to_json(const SideMetrics& side);

//! Rounds to 12 significant digits for stable JSON output (non-finite values become 0 and are a bug upstream).
double round_for_json(double value);

}  // namespace stiffpath::evaluation
