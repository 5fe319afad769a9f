// Measuring a calibration plate's arc on its registered scan (radial profiles across the mark); not installed.
#pragma once

#include <string>
#include <vector>

#include "stiffpath/vision/scan/plate_marks.hpp"

namespace stiffpath::vision::detail {

//! The centre line of `arc` (a StrokeKind::arc mark) on `grey`, registered by `registration`: every 0.1 mm along the
//! commanded circle, short of each end by `trim_m`, the ink's darkness-weighted centre along the radius (the mean of
//! five profiles a pixel apart along the arc) within
//! ±half_width_m of the circle (around its darkest point, ±0.3 mm). Points in the robot frame, in marking order; a
//! profile without ink (darkness under a quarter of the paper's level) gives no point. `why` says what went wrong
//! when fewer than half of the profiles found ink (the points are then empty).
std::vector<Eigen::Vector2d> measure_arc(const calibration::StrokeMark& arc, const cv::Mat& grey, double dpi,
                                         const PlateRegistration& registration, double half_width_m, double trim_m,
                                         std::string& why);

}  // namespace stiffpath::vision::detail
