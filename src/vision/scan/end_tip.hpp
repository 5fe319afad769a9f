// The tip of a free end of the mark: its farthest dark pixel and the blurred round spot fitted there; not installed.
#pragma once

#include <cstddef>
#include <optional>

#include "scan_internal.hpp"

namespace stiffpath::vision::detail {

//! Where to look for a free end's tip: pixels connected to `seed` (a point on the mark, image px) inside
//! `box` whose darkness 1 − I/paper (the coarse grid's paper level) exceeds `threshold`.
struct TipSearch {
  Point2 seed{0, 0};
  cv::Rect box;
  Point2 outward{1, 0};  //!< unit vector along the side, pointing out of the mark at this end
  double threshold = 0;
  double seed_reach_px = 0;    //!< the flood starts at the darkest pixel within this distance across the seed
};
//! The farthest such pixel along `outward`.
struct TipExtreme {
  Point2 point{0, 0};        //!< its centre (image px), moved across to the darkness-weighted centre of the pixels within 1.5 px of the extreme
  bool at_box_edge = false;  //!< a dark pixel that far out lies on the box's edge: the mark may go on outside the box
};
//! nullopt if no pixel near the seed is dark.
std::optional<TipExtreme> farthest_dark_point(const cv::Mat& grey, const CoarseGrid& grid, const TipSearch& search);

//! Start values of the tip fit (image px).
struct TipGuess {
  Point2 centre{0, 0};   //!< centre of the spot at the tip
  Point2 outward{1, 0};  //!< unit vector along the side, out of the mark
  double radius = 0;     //!< the spot's radius w/2
  double darkness = 0;   //!< full darkness k of the mark
  double sigma = 0;      //!< edge spread: blur and pixel area, √(σ_blur² + 1/12)
  double half_angle_rad = 0;  //!< the fitted part of the edge, about `outward` (ScanTuning::tip_half_angle_deg)
};

//! A blurred disk fitted to the outermost edge of the mark's footprint (see blurred_disk.hpp).
struct TipFit {
  Point2 centre{0, 0};  //!< the fitted circle's centre (image px)
  double radius = 0;    //!< its radius R (px); a round spot that stops or turns back sharply gives w/2
  double darkness = 0;  //!< the fitted full darkness k
  double rms = 0;       //!< rms residual darkness over the fitted pixels, relative to k
  std::size_t pixels = 0;
  bool converged = false;
};
//! Gauss–Newton fit of darkness = a + b·blurred_disk(|p − c|; R, σ) to the pixels within half_angle of
//! `outward` seen from c and within 3σ + 1 px of the circle (window rebuilt for the first iterations).
//! The footprint of a round spot moved along any path is the union of its disks, so near the point
//! farthest along `outward` its edge is a circle of radius ≥ w/2; its extent along `outward` is c·u + R.
TipFit fit_end_tip(const cv::Mat& grey, const CoarseGrid& grid, const TipGuess& guess);

}  // namespace stiffpath::vision::detail
