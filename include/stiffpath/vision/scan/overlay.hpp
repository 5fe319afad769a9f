// Overlay picture of a scan measurement, like thesis fig. 4.8: centre line, fitted line, spline, magnified deviation, legend, scale.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::vision {

//! Where an overlay put its parts (px of the overlay picture), so that they can be checked.
struct OverlayLayout {
  double scale = 1;      //!< overlay px per scan px (below 1 for scans above 25 Mpx, drawn smaller)
  int text_height_px = 0;
  cv::Size size;         //!< the whole picture
  cv::Rect scan;         //!< the scan's place
  cv::Rect legend;       //!< the legend (with the scale bar)
  std::vector<std::string> legend_entries;
  cv::Rect scale_bar;    //!< the bar itself; its length is scale_bar_mm at the picture's scale
  double scale_bar_mm = 0;
  struct Text {
    std::string text;
    cv::Rect box;
  };
  std::vector<Text> texts;             //!< every text drawn, with the box it covers
  std::vector<cv::Rect> strips;        //!< plot areas of the deviation strips, one per side
  std::vector<cv::Rect> side_numbers;  //!< the numbered discs that name the sides on the scan
};

//! Returns a BGR 8-bit picture: a legend with a scale bar in mm above the scan (grey), drawn with the
//! detected centre line (green), each side's fitted line (blue), its smoothing spline (red), the
//! corners (yellow) and each side's number; below it one strip per side plotting the spline's offset
//! from the line magnified (the centre-line points in grey), with mm ticks along the side, the offset's
//! scale in µm and a caption with the magnification and the metrics. Text is sized to the picture
//! (about 1/80 of its larger side) and the strips are at least 44 text heights wide, so the picture
//! reads at any aspect ratio; scans above 25 Mpx are drawn at a smaller scale (stated in the legend).
//! `layout`, when given, receives where everything went.
cv::Mat draw_overlay(const cv::Mat& grey, const ScanResult& result, OverlayLayout* layout = nullptr);

//! The same for a plate: every mark's bounding box (green: measured, orange: skipped) with its number,
//! the label areas (grey), the measured marks drawn as above with a strip per side, and a list of the
//! skipped marks with their reasons.
cv::Mat draw_plate_overlay(const cv::Mat& grey, const PlateResult& plate, OverlayLayout* layout = nullptr);

}  // namespace stiffpath::vision
