// Metrics of a marked path (thesis §4.7): length between start and end, deviation-from-linearity area, max deviation.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "stiffpath/evaluation/line_fit.hpp"
#include "stiffpath/evaluation/smoothing_spline.hpp"

namespace stiffpath::evaluation {

//! Whether a path returns to its start (a triangle) or not (a line, an open polyline).
enum class Closure { automatic, open, closed };

//! Options of the path metrics. All lengths in m.
struct PathMetricsOptions {
  //! Cutoff wavelength L_c of the smoothing spline (see SmoothingSpline): deviations with a longer
  //! wavelength are kept, shorter ones (scan noise, paper texture) removed. 0 = interpolating
  //! spline, for exact densely sampled paths (simulation ground truth).
  double smoothing_cutoff_m = 1e-3;
  //! Points closer than this to a corner are left out of a side's line, spline and area, so a
  //! rounded or overshooting corner does not tilt the sides. Free ends are never trimmed.
  double corner_trim_m = 1e-3;
  //! measure_path only: open/closed, or automatic (closed when the gap between the first and last
  //! point is below closed_gap_fraction × path length / sides, for three or more sides).
  Closure closure = Closure::automatic;
  double closed_gap_fraction = 0.05;
  //! Every side is measured along its mark: the polyline through its points is resampled at equal
  //! arc-length steps of at most this (m) and the line, spline, area and deviations are taken on those
  //! samples, so each part of the mark weighs by its length, whatever the spacing of the points given
  //! (a simulated mark sampled in time, a scan's cross-sections). 20 µm: finer than a 1200 dpi pixel.
  double resample_step_m = 20e-6;
  //! Points within this of the polyline through the others are dropped first (m); free ends and
  //! corner distances are taken on what is kept, so they are exact within twice this.
  double trace_tolerance_m = 1e-9;
};

//! Consecutive sides whose fitted lines meet at an interior angle below this (rad, 10°) are joined by a
//! reversal (a hatch's turn): their lines' intersection is no corner, and both ends there are free ends.
inline constexpr double kReversalAngle_rad = 0.17453292519943295;

//! One straight side of a path, measured in its own fitted line's frame (t along, u across).
struct SideMetrics {
  LineFit fit;               //!< TLS line of the side's (trimmed) points, direction from start to end
  SmoothingSpline spline;    //!< smoothing spline u(t) of the offsets from the line
  Point2 start{0, 0};        //!< start on the line: the corner, or the free end's extreme projection (m)
  Point2 end{0, 0};          //!< end on the line, likewise (m)
  bool start_is_corner = false;
  bool end_is_corner = false;
  double length_m = 0;           //!< |end − start|: length between start and end (§4.7)
  double deviation_area_m2 = 0;  //!< ∫|u(t)| dt between spline and line over [t_from, t_to] (§4.7)
  double max_deviation_m = 0;    //!< max |u(t)| of the spline over the same range
  double straightness_m = 0;     //!< peak to valley, max u − min u of the spline
  //! Largest |u| of the samples themselves, unsmoothed: how far the side's points stray from its line
  //! (a side that is no straight line, such as an arc, whose u(t) has two values, shows here).
  double max_offset_m = 0;
  double t_from_m = 0, t_to_m = 0;  //!< along-line range of the metrics (t = 0 at the fit's centroid)
  std::size_t point_count = 0;      //!< points used (after corner trimming)
};

//! A corner between two consecutive sides.
struct CornerReport {
  Point2 position{0, 0};      //!< intersection of the two sides' fitted lines (m)
  double angle_rad = 0;       //!< interior angle between the sides (π = no corner, π/3 in an equilateral triangle)
  std::size_t side_before = 0, side_after = 0;
  //! Distance from `position` to the nearest given path point (m): how far a rounded or cut corner
  //! stays from the ideal one. nullopt when the caller's points do not reach the corner (scans).
  std::optional<double> path_distance_m;
};

//! Metrics of a whole path: its sides in order, the corners between them and the totals.
struct PathMetrics {
  std::vector<SideMetrics> sides;
  //! N − 1 for an open path, N for a closed one (corner k ends side k), less one per reversal
  std::vector<CornerReport> corners;
  bool closed = false;
  double length_m = 0;           //!< sum of the sides' lengths
  double deviation_area_m2 = 0;  //!< sum of the sides' areas (the thesis's triangle total, §4.7)
  double max_deviation_m = 0;    //!< largest side maximum
  double straightness_m = 0;     //!< largest side peak to valley
};

//! Measures a path already separated into sides (each side's points ordered from its start to its
//! end), along the mark (PathMetricsOptions::resample_step_m). For a closed path the last side ends at
//! the first side's start. Corners are the intersections of consecutive sides' TLS lines, refined
//! twice after trimming the points near them; sides meeting at less than kReversalAngle_rad have free
//! ends there instead. The work is SideChain's (the same numbers side by side in bounded memory).
//! Throws stiffpath::Error when a side has fewer than two usable points, consecutive sides are
//! parallel, or a side comes out with non-positive length.
PathMetrics measure_sides(const std::vector<std::vector<Point2>>& sides, bool closed, const PathMetricsOptions& options = {});

//! Measures an ordered path (points in the order they were marked, in m) as `n_sides` straight
//! sides: 1 for a line, 3 for a triangle. Corners are found by split_polyline.
PathMetrics measure_path(std::span<const Point2> points, int n_sides, const PathMetricsOptions& options = {});

//! An ordered path cut into sides at its corners.
struct PolylineSplit {
  bool closed = false;
  std::vector<std::vector<Point2>> sides;  //!< consecutive sides share their corner point
};

//! Cuts an ordered path into `n_sides` pieces at its corners: a greedy farthest-point split
//! (Ramer–Douglas–Peucker until there are n pieces), then each cut moved to the path point nearest
//! the intersection of its neighbouring sides' fitted lines. A closed path is first rotated to start
//! at a corner. Throws stiffpath::Error when there are too few points for the sides asked for.
PolylineSplit split_polyline(std::span<const Point2> points, int n_sides, const PathMetricsOptions& options = {});

}  // namespace stiffpath::evaluation
