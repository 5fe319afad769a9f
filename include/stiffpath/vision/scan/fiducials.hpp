// Fiducials on a scanned plate: rings (with an optional cross) marked slowly, whose centres register the scan to the robot.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "stiffpath/evaluation/path_metrics.hpp"

namespace stiffpath::vision {

using evaluation::Point2;

//! A fiducial's shape: a ring (a circle marked by the laser spot), optionally with a cross inside whose arms
//! stop short of the ring. A ring's centre is precise (every point of it is measured, the blur and the
//! spot's size do not move it) and unambiguous (no side, no end, no orientation); the cross tells a
//! fiducial from a round letter or a stray circle.
struct FiducialShape {
  double ring_radius_m = 3e-3;  //!< radius of the ring's centre line (m)
  bool cross = true;            //!< a cross at the centre
  double cross_arm_m = 1.5e-3;  //!< half length of each of the cross's two strokes (m); must stop short of the ring
  //! Throws stiffpath::Error (starting with `what`) for a radius outside 0.5–50 mm, or arms that reach the ring
  //! for a mark of `mark_width_m`.
  void check(const std::string& what, double mark_width_m) const;
};

//! A fiducial found on a scan.
struct Fiducial {
  Point2 centre_m{0, 0};    //!< centre (m, image frame: x right, y down from the image's top-left corner)
  double uncertainty_m = 0; //!< standard uncertainty of the centre along each axis (m): the circle fit's, from its residuals
  double radius_m = 0;      //!< measured radius of the ring's centre line (m)
  double rms_m = 0;         //!< rms distance of the ring's centre line from the fitted circle (m)
  double width_m = 0;       //!< the ring's mark width (m)
  bool cross = false;       //!< a cross was found at the centre
};

//! What to look for.
struct FiducialSearch {
  FiducialShape shape;
  //! How many fiducials the plate has; 0: any number (at least one). More rings of the shape than this is an
  //! ambiguity, fewer a missing fiducial: both refused with the reason.
  int expected = 0;
  double radius_tolerance = 0.1;  //!< a ring whose radius is off the shape's by more (fraction) is not a fiducial
  std::string label = "<image>";  //!< names the image in errors
  cv::Rect roi_px;                //!< look only inside this region (px; empty = the whole image)
};

//! Finds the fiducials on a grey scan (CV_8U or CV_16U) at `dpi`, in reading order (top to bottom, then left to
//! right). Each dark feature of the ring's size is checked: a ring (dark along a circle of the expected radius,
//! paper inside), its cross when the shape has one; its centre comes from a least-squares circle through the
//! ring's sub-pixel centre line (one point per half-degree of the ring). Throws stiffpath::Error with the
//! reason, naming each candidate and what it lacked, when fewer are found than expected or none, and when
//! more rings of the shape are found than expected (ambiguous).
std::vector<Fiducial> find_fiducials(const cv::Mat& grey, double dpi, const FiducialSearch& search);

}  // namespace stiffpath::vision
