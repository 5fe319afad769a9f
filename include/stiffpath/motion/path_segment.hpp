// One piece of the path in the robot frame (line, arc or dwell) with its feed, laser state and source line.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>

#include "stiffpath/motion/limits.hpp"

namespace stiffpath::motion {

enum class SegmentKind : std::uint8_t {
  line,   //!< straight from start_m to end_m
  arc,    //!< circular arc about center_m (G2/G3, or a corner blend)
  dwell,  //!< standing still for dwell_s (G4)
};

//! Moves shorter than this (1 nm) are dropped by the reader and absorbed by corner blends: their
//! durations would fall below the resolution of the program clock.
inline constexpr double shortest_segment_m = 1e-9;

//! How the junction at the end of a segment is passed (G-code path control mode).
enum class JunctionMode : std::uint8_t {
  exact_stop,  //!< G61: come to rest at every corner (tangent junctions are passed without stopping)
  blend,       //!< G64 P: round corners between lines within blend_tolerance_m
};

//! A path segment, SI units, robot frame. Lines and arcs have length_m > 0; dwells have length 0.
struct PathSegment {
  SegmentKind kind = SegmentKind::line;
  Vec2 start_m = Vec2::Zero();   //!< first point (m)
  Vec2 end_m = Vec2::Zero();     //!< last point (m), exactly the programmed end point
  Vec2 center_m = Vec2::Zero();  //!< arcs: centre of the circle (m)
  double radius_m = 0.0;         //!< arcs: radius (m)
  double start_angle_rad = 0.0;  //!< arcs: polar angle of start_m about center_m (rad)
  double sweep_rad = 0.0;        //!< arcs: signed swept angle, > 0 counter-clockwise (G3), < 0 clockwise (G2)
  double length_m = 0.0;         //!< path length (m)
  double feed_m_s = std::numeric_limits<double>::infinity();  //!< requested speed F (m/s); +inf for G0
  double dwell_s = 0.0;          //!< dwells: duration (s)
  //! Laser power as a fraction of full power, 0..1 (S / s_max, M106 S / 255, or 1 for M62), 0 when
  //! the laser is off. With dynamic_power it is the power at the programmed feed.
  double power = 0.0;
  double blend_tolerance_m = 0.0;  //!< G64 P (m): how far a blended corner may leave the corner point
  //! G64 Q (m), at most P/2: how far a chain of short lines merged into one (LineMerger) may pass from
  //! their vertices; the blend of the merged line then keeps within P minus this. 0: never merged.
  double merge_tolerance_m = 0.0;
  //! M204 S: the program's acceleration limit for this segment (m/s²), below the machine's; 0: the machine's.
  double max_acceleration_m_s2 = 0.0;
  int line = 0;                  //!< 1-based source line of the G-code block
  bool rapid = false;            //!< G0
  bool laser_on = false;         //!< laser firing: M3/M4 (M106, M62) active, power > 0 and not a G0 move
  bool dynamic_power = false;    //!< M4 (GRBL's laser mode): power scaled by speed / feed_m_s, see power_at
  bool merged = false;           //!< a line LineMerger made of several (a staircase's, fine chords')
  JunctionMode mode = JunctionMode::exact_stop;  //!< how the junction at the end of this segment is passed
};

//! The geometry at arc length s along a segment.
struct PathPoint {
  Vec2 position_m = Vec2::Zero();
  Vec2 tangent = Vec2::UnitX();    //!< unit tangent in the direction of motion
  double curvature_1_m = 0.0;      //!< signed curvature κ (1/m): > 0 turning left (counter-clockwise)
};

//! A straight segment. length_m = |end − start|.
PathSegment make_line(const Vec2& start_m, const Vec2& end_m);
//! An arc from start_m about center_m through the signed angle sweep_rad, ending exactly at end_m
//! (the caller guarantees |end − centre| = |start − centre| up to rounding).
PathSegment make_arc(const Vec2& start_m, const Vec2& end_m, const Vec2& center_m, double sweep_rad);

//! `piece` (a line or arc that replaces part of `source`) with source's feed, laser state and power,
//! blend and merge tolerances, source line, rapid flag and junction mode.
PathSegment carrying_attributes(PathSegment piece, const PathSegment& source) noexcept;
//! A dwell of duration_s at point_m.
PathSegment make_dwell(const Vec2& point_m, double duration_s);

//! Position, unit tangent and curvature at arc length s (clamped to [0, length]); s ≥ length gives
//! exactly end_m. Dwells give their point with tangent +x.
PathPoint point_at(const PathSegment& segment, double s_m) noexcept;

//! Distance from p to the straight segment from a to b (a ≠ b), m.
double distance_to_segment_m(const Vec2& p, const Vec2& a, const Vec2& b) noexcept;
//! Unit tangent where the segment starts / ends.
Vec2 start_tangent(const PathSegment& segment) noexcept;
Vec2 end_tangent(const PathSegment& segment) noexcept;
//! Signed curvature (1/m): 0 for lines, ±1/radius for arcs.
double curvature_1_m(const PathSegment& segment) noexcept;

//! The laser power (fraction 0..1) on a segment at path speed v: `power` with M3, and with M4
//! (dynamic) power · min(1, v / feed), so the energy per unit length stays that of the feed
//! (GRBL's laser mode: power scaled by the current over the programmed rate). 0 when the laser is off.
double power_at(const PathSegment& segment, double speed_m_s) noexcept;

//! The left normal of a unit vector (rotated by +90°).
inline Vec2 left_normal(const Vec2& u) noexcept { return {-u.y(), u.x()}; }

}  // namespace stiffpath::motion
