// A scanned calibration plate: its fiducials register the scan to the robot frame, its strokes measured in robot metres.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "stiffpath/calibration/identify.hpp"
#include "stiffpath/calibration/plate.hpp"

namespace stiffpath::vision {

//! The most fiducials a plate may have: every assignment of the found ones to the plate's is tried (8! · 2).
inline constexpr std::size_t kMaxPlateFiducials = 8;

//! Scan (m of the image, from its top-left corner, x right, y down) → robot frame (m): robot = linear·scan + t.
struct PlateRegistration {
  //! A rotation times a mirror (det −1) for a scan that shows the sheet as seen from above (the image's y runs
  //! down, the robot's up); a rotation alone (det +1) for a scan that shows it mirrored.
  Eigen::Matrix2d linear = Eigen::Matrix2d::Identity();
  Eigen::Vector2d translation_m = Eigen::Vector2d::Zero();
  bool mirrored = false;                                 //!< the scan shows the sheet mirrored (det(linear) = +1)
  double residual_rms_m = 0, residual_max_m = 0;          //!< of the fiducial centres after the fit
  int fiducials = 0;                                      //!< how many were found and used
  //! A scan point in the robot frame.
  [[nodiscard]] Eigen::Vector2d to_robot(const Eigen::Vector2d& scan_m) const;
  //! A robot point on the scan (the inverse).
  [[nodiscard]] Eigen::Vector2d to_scan(const Eigen::Vector2d& robot_m) const;
};

//! Settings of observe_calibration_plate. Documented defaults (docs/vision.md, "Registering a calibration plate").
struct PlateScanOptions {
  //! Each stroke is looked for within this distance of its commanded path (mapped into the scan): it covers a
  //! deflection of ~1 mm and the tail's wave, and stays under the 1.5 mm the plate keeps clear between marks.
  double corridor_half_width_m = 1.4e-3;
  //! A registration whose fiducial residual (rms) exceeds this is refused: the scan is distorted, or a
  //! fiducial was found off its ring.
  double max_residual_m = 50e-6;
  //! When two assignments of the fiducials fit within max_residual_m (a symmetric layout), the strokes decide:
  //! the fraction of each one's commanded path with ink nearby. Closer than this, the match is ambiguous.
  double min_ink_margin = 0.25;
  //! Corner trim of the strokes' centre line (the tail's corner): points closer to the corner are not measured.
  double corner_trim_m = 1e-3;
  //! Resolution of the scan when given (dpi); 0: the file's own (load_scan's rules).
  double dpi = 0;
};

//! What a scanned plate says.
struct PlateObservation {
  PlateRegistration registration;
  std::vector<calibration::ObservedMark> marks;  //!< one per plate stroke found, in plate order
  std::vector<std::string> warnings;             //!< a stroke not found or cut short, with its id and why
};

//! Registers a scan of `plate` and measures its strokes: finds every fiducial (vision::find_fiducials with the
//! plate's shape), tries every assignment to the plate's fiducials with and without a mirror (rigid, scale from
//! the resolution; least squares, Kabsch), keeps the one of smallest residual — the strokes' ink decides between
//! assignments a symmetric layout fits equally well — then measures each stroke's centre line (analyse_scan's
//! cross-sections and free ends) inside a corridor around its commanded path and maps it to the robot frame,
//! ordered from the stroke's start (through its tail). Throws stiffpath::Error naming the file and the reason for
//! an unreadable image or resolution (load_scan), a plate with fewer than 3 or more than kMaxPlateFiducials
//! fiducials, a fiducial missing or one too many, an ambiguous match, or a residual above options.max_residual_m.
PlateObservation observe_calibration_plate(const calibration::PlateDesign& plate, const std::filesystem::path& scan,
                                           const PlateScanOptions& options = {});

//! The same on an image in memory (grey, CV_8U or CV_16U) at `dpi`; `label` names it in errors and warnings.
PlateObservation observe_calibration_plate(const calibration::PlateDesign& plate, const cv::Mat& grey, double dpi,
                                           const std::string& label, const PlateScanOptions& options = {});

}  // namespace stiffpath::vision
