// A ring's sub-pixel centre line along rays from its centre, and the least-squares circle through it; not installed.
#pragma once

#include <vector>

#include "scan_internal.hpp"

namespace stiffpath::vision::detail {

//! Darkness 1 − I/paper at a point (image px, continuous: pixel (c, r) spans [c, c+1) × [r, r+1)), bilinear
//! between pixel centres; 0 outside the image.
double darkness_at(const cv::Mat& grey, const CoarseGrid& grid, const Point2& p);

//! The ring seen from a centre guess.
struct RingFit {
  Point2 centre{0, 0};           //!< the fitted circle's centre (px)
  double radius = 0;             //!< its radius (px)
  double rms = 0;                //!< rms distance of the centre-line points from the circle (px)
  double width = 0;              //!< the ring's mark width (px): darkness integral across it over its peak darkness
  double darkness = 0;           //!< the ring's peak darkness (median over the rays)
  double covered = 0;            //!< share of the rays that crossed the ring (a broken ring or a C lacks some)
  std::size_t points = 0;        //!< centre-line points fitted
  bool ok = false;               //!< enough points for a fit
};

//! Measures a ring of radius about `radius_px` around `centre` (px), the radius within ±`radius_slack_px`:
//! the mean radial darkness profile gives the ring's radius and width; along each of 720 rays, the
//! darkness-weighted centroid over the ring's width + the blur gives a centre-line point; a circle is fitted
//! to them (algebraically, then by Gauss–Newton on the distances) and the rays recentred on it, three times.
RingFit fit_ring(const cv::Mat& grey, const CoarseGrid& grid, Point2 centre, double radius_px, double radius_slack_px);

}  // namespace stiffpath::vision::detail
