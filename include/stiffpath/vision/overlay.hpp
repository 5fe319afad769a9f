// Overlay picture of a scan measurement, like thesis fig. 4.8: centre line, fitted line, spline, magnified deviation.
#pragma once

#include <opencv2/core.hpp>

#include "stiffpath/vision/scan.hpp"

namespace stiffpath::vision {

//! Returns a BGR 8-bit picture: the scan (grey) with the detected centre line (green), each side's
//! fitted line (blue), its smoothing spline (red) and the corners (yellow circles) drawn at true
//! scale, and below it one strip per side plotting the spline's offset from the line magnified to
//! fill the strip (the centre-line points in grey), labelled with the magnification and metrics.
cv::Mat draw_overlay(const cv::Mat& grey, const ScanResult& result);

}  // namespace stiffpath::vision
