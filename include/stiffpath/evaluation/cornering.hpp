// ISO 9283:1998 §7.8 cornering deviations of an attained path at the sharp corners of its commanded path.
#pragma once

#include <span>
#include <vector>

#include "stiffpath/evaluation/line_fit.hpp"

namespace stiffpath::evaluation {

//! The deviations of one attained path at one sharp corner of the command. SI.
struct CorneringDeviation {
  Point2 corner{0.0, 0.0};    //!< the commanded corner point (m)
  double turn_rad = 0.0;      //!< change of direction at the corner (0 = straight on, π = reversal)
  double round_off_m = 0.0;   //!< CR: distance from the corner point to the nearest point of the attained path
  //! CO: how far the attained path goes outside the outgoing side's line near the corner (0 if never):
  //! the largest offset from that line on the side the incoming motion came from (inertia's side).
  double overshoot_m = 0.0;
  //! Whether the attained path entered the corner's neighbourhood. If not, CR is its distance from
  //! the corner (at least the neighbourhood's radius) and CO is 0: there is no overshoot to measure.
  bool reached = true;
};

//! Options of the cornering evaluation.
struct CorneringOptions {
  //! A vertex of the command is a corner when the direction turns by more than this (rad, 10°).
  double min_turn_rad = 0.17453292519943295;
  //! Points of the command closer together than this are merged before directions are taken (m),
  //! so that the dense samples of a move coming to rest do not make up directions of their own.
  double merge_distance_m = 1e-6;
  //! Vertices of the command joined by segments shorter than this (m), between straight sides at least
  //! this long, form one corner at the sides' intersection: a corner rounded by a few µm (a smoothed
  //! reference at an exact stop, a small G64 blend) is still the corner the sides meet at. Arcs and
  //! fillets wider than this are no corners.
  double max_corner_span_m = 0.5e-3;
  //! The neighbourhood of a corner is this fraction of the shorter adjacent side: the attained
  //! points inside it (in the order marked, from their first entry to their last exit) count.
  double neighbourhood_fraction = 0.5;
};

//! Finds the sharp corners of `command` (interior vertices, or runs of vertices within max_corner_span_m,
//! that turn by more than min_turn_rad; filleted corners wider than that turn gradually and are not corners) and measures `attained` (points in m in
//! the order marked) at each, in order along the command. Endpoints of the command are not corners,
//! even when it closes on itself. Returns no entries for a command without sharp corners. Throws
//! stiffpath::Error for fewer than two attained points, a command shorter than two distinct points,
//! or non-finite coordinates.
std::vector<CorneringDeviation> iso9283_cornering(std::span<const Point2> command, std::span<const Point2> attained,
                                                  const CorneringOptions& options = {});

}  // namespace stiffpath::evaluation
