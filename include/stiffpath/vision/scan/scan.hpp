// Measuring a laser-marked path on a scan (thesis §4.6): segmentation, sub-pixel centre line, px → m, path metrics.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "stiffpath/evaluation/path_metrics.hpp"
#include "stiffpath/vision/scan/tuning.hpp"

namespace stiffpath::vision {

using evaluation::Point2;

//! Options of the scan analysis.
struct ScanOptions {
  //! Straight sides of the path: 1 a line, 3 a triangle, N a polyline; 0 = any: a straight line, else
  //! the fewest straight sides (up to max_auto_sides) that join into one chain or loop.
  int sides = 1;
  int max_auto_sides = 4;  //!< most sides tried for sides = 0 (lines, corners, triangles, quadrilaterals)
  //! Spline cutoff wavelength and corner trim of the metrics (defaults 1 mm and 1 mm).
  evaluation::PathMetricsOptions metrics;
  double min_mark_length_m = 1e-3;  //!< dark features smaller than this are dust specks
  std::string label = "<image>";    //!< names the image in errors
  //! Analyse only this region of the image (px; empty = the whole image). Every position reported
  //! stays in the whole image's frame; a mark touching the region's edge is refused like one on the
  //! image's border.
  cv::Rect roi_px;
  //! analyse_plate: dark features smaller than this across are listed as labels or fragments, not measured.
  double min_plate_mark_m = 10e-3;
  //! Called now and then with the fraction of the work done (0..1), from the calling thread; may be empty.
  std::function<void(double)> progress;
  //! The method's tuning constants (cell size, windows, tolerances); the defaults are the documented method.
  ScanTuning tuning;
};

//! What the scan says about one side beyond the path metrics.
struct ScanSide {
  double width_m = 0;              //!< median width of the mark's cross-sections (m)
  std::vector<Point2> centres;     //!< sub-pixel centre-line points (m, image frame), cap centres of free ends included
  std::size_t sections = 0;        //!< cross-sections measured
  std::size_t rejected_sections = 0;  //!< left out as outliers (dust on the mark, gaps)
};

//! Result of analyse_scan. Coordinates are in the image frame: x to the right, y down, origin at
//! the top-left corner of the top-left pixel, in m.
struct ScanResult {
  evaluation::PathMetrics metrics;  //!< length, deviation area, max deviation, straightness, sides, corners
  std::vector<ScanSide> sides;      //!< same order as metrics.sides
  double width_m = 0;               //!< median mark width over all sides (m)
  //! Bound on the length's error from free ends that are not round laser-spot ends (m): 0 when every
  //! free end is round (then the length is good to a few µm, docs/vision.md), else the sum of their
  //! bounds, each also stated in a warning.
  double length_uncertainty_m = 0;
  double mark_darkness = 0;         //!< 1 − mark/paper brightness of the fully marked core
  double paper_noise = 0;           //!< robust σ of the paper's relative brightness at the coarse grid
  int specks_ignored = 0;           //!< dark features below min_mark_length_m that were ignored
  double dpi = 0;
  int width_px = 0, height_px = 0;
  std::vector<std::string> warnings;  //!< conditions that may bias the numbers (never silently)
};

//! Measures the one marked path on a grey scan (CV_8U or CV_16U) at `dpi`. Steps: coarse
//! background (block medians on a 4 px grid) and dark-feature segmentation; the largest feature is
//! the mark (a second one of ≥ 20 % its size, or the mark touching the border, is an error; small
//! ones are specks); its sides by a line fit (one side) or sequential RANSAC (several), corners by
//! intersecting them; per side, cross-sections along the image axis nearer its normal: local
//! paper level from the flanks, darkness 1 − I/paper, intensity-weighted centroid (sub-pixel
//! centre) and darkness integral (width); free ends at the mark's farthest point along the side, from
//! a blurred round laser spot fitted to the footprint's tip (hooked or overshooting ends included;
//! see docs/vision.md). Throws stiffpath::Error naming
//! options.label for an empty image, no mark, two marks, a mark on the border, or a mark that does
//! not split into the requested sides.
ScanResult analyse_scan(const cv::Mat& grey, double dpi, const ScanOptions& options = {});

//! The frame of every position a scan reports, in words (for files that carry positions).
inline constexpr const char* kCentreLineFrame =
    "mm of the scan from the top-left corner of its image (of the whole image, also with a region), x right, y down";

//! The result with units in the keys: evaluation::to_json(metrics) plus width_mm (and per side),
//! dpi, image size, mark darkness, specks ignored, rejected sections, the warnings and the centre line
//! (centre_line_json).
nlohmann::json to_json(const ScanResult& result);

//! Each side's centre line: {"frame": kCentreLineFrame, "sides_mm": [[[x, y], …], …]}, the points in marking
//! order from the side's start (a free end's first or last point is the path's end there: the round spot's
//! centre), rounded to 0.1 µm.
nlohmann::json centre_line_json(const ScanResult& result);

//! The shape measured, in the words of ScanOptions: "line", "triangle" (three sides, closed) or "polyline:N".
std::string shape_name(const ScanResult& result);

//! The sides and closure of a shape named in those words.
struct ScanShape {
  int sides = 1;                                              //!< ScanOptions::sides (0 = any)
  evaluation::Closure closure = evaluation::Closure::automatic;  //!< PathMetricsOptions::closure
};
//! Parses "line" (1 side, open), "triangle" (3 sides, closed), "polyline:N" (N sides, N in 1..64, closure
//! found on the scan) or "any" (sides found on the scan). Throws stiffpath::Error starting with `what`
//! (the option's name, e.g. "--shape") for anything else.
ScanShape parse_scan_shape(const std::string& shape, const std::string& what);

//! One dark feature of a plate and what became of it.
struct PlateMark {
  int index = 0;          //!< 1-based, in the order of the features' top edges (reading order)
  cv::Rect2d box_m;       //!< bounding box in the image frame (m): x, y of its top-left corner, width, height
  bool measured = false;
  std::string reason;     //!< why it was not measured (a label too small to be a mark, a shape that is not one, …)
  ScanResult result;      //!< the measurement, when measured
};

//! Lettering on a plate: dark features smaller than a mark, grouped where they stand close together.
struct PlateLabelArea {
  cv::Rect2d box_m;   //!< bounding box of the group (m, image frame)
  int features = 0;   //!< dark features in it (letters, or strokes of letters)
};

//! A dark feature that is not a laser mark: the edge of the paper on the scanner's lid, a smudge, a shadow.
struct PlateIgnored {
  cv::Rect2d box_m;    //!< bounding box (m, image frame)
  std::string reason;  //!< what it is taken for, and why
};

//! Every mark of a plate.
struct PlateResult {
  std::vector<PlateMark> marks;       //!< features at least min_plate_mark_m across
  std::vector<PlateLabelArea> labels; //!< smaller features (≥ min_mark_length_m), grouped: labels, lettering, fragments
  std::vector<PlateIgnored> ignored;  //!< features (≥ min_mark_length_m) that are not marks: the paper's edge, smudges
  int specks_ignored = 0;             //!< dark features smaller than min_mark_length_m
  double dpi = 0;
  int width_px = 0, height_px = 0;
  double paper_noise = 0;
};

//! Measures every mark on a scan of a plate (or of options.roi_px) holding several: each dark feature at
//! least options.min_plate_mark_m across that does not touch the border is measured as options.sides
//! says (0 = find its shape); marks that are not straight lines or polylines, or cannot be measured, are
//! listed with the reason. Smaller features (labels, lettering, fragments) are grouped into label areas
//! (features whose boxes are closer than the taller one's height) and not measured. Throws
//! stiffpath::Error only for a bad image or options.
PlateResult analyse_plate(const cv::Mat& grey, double dpi, const ScanOptions& options = {});

//! The plate as JSON: image size, dpi, specks ignored, one entry per mark with box_mm
//! [x, y, width, height], status "measured" (with shape and the keys of to_json(ScanResult)) or
//! "skipped" (with reason), the label areas (box_mm, features) and the features ignored as not marks
//! (box_mm, reason).
nlohmann::json to_json(const PlateResult& plate);

}  // namespace stiffpath::vision
