// Registering a scanned calibration plate to the robot frame from its fiducials; not installed.
#pragma once

#include <string>

#include "stiffpath/vision/scan/plate_marks.hpp"

namespace stiffpath::vision::detail {

//! Finds the plate's fiducials on `grey`, matches them to the plate's (every assignment, with and without a
//! mirror; the strokes' ink decides between symmetric ones) and fits the rigid transform. Throws
//! stiffpath::Error starting with `label` for the reasons observe_calibration_plate lists.
PlateRegistration register_plate(const calibration::PlateDesign& plate, const cv::Mat& grey, double dpi,
                                 const std::string& label, const PlateScanOptions& options);

//! The fraction of the plate's commanded stroke paths (sampled every 0.5 mm) with a dark pixel within the
//! corridor across them, on the scan placed by `registration`: ~1 for the right placement, small for a wrong one.
double stroke_ink(const calibration::PlateDesign& plate, const cv::Mat& grey, double px_per_m,
                  const PlateRegistration& registration, double corridor_half_width_m);

}  // namespace stiffpath::vision::detail
