// The speed cap and tangential acceleration/jerk limits of one segment, arcs sharing the budget with centripetal terms.
#pragma once

#include "stiffpath/motion/limits.hpp"
#include "stiffpath/motion/path_segment.hpp"

namespace stiffpath::motion {

//! Limits for the profile along one segment (all along the path's tangent).
struct SegmentLimits {
  double max_velocity_m_s = 0.0;       //!< speed cap (m/s): min(F, machine limit), lower on tight arcs
  double max_acceleration_m_s2 = 0.0;  //!< tangential acceleration limit (m/s²)
  double max_jerk_m_s3 = 0.0;          //!< tangential jerk limit (m/s³)
};

//! Shares of the machine limits an arc may give to its normal (centripetal) terms. On an arc of
//! curvature κ at speed v with tangential acceleration a_t and jerk j_t the path's vectors are
//!   acceleration = a_t·T + v²κ·N,   jerk = (j_t − v³κ²)·T + 3·v·κ·a_t·N.
//! The cap v_c keeps v_c²κ ≤ 0.7·a and v_c³κ² ≤ 0.3·j; then a_t = sqrt(a² − (v_c²κ)²), lowered
//! until 3·v_c·κ·a_t ≤ 0.6·j, and j_t = sqrt(j² − (3·v_c·κ·a_t)²) − v_c³κ² (≥ 0.5·j). So |a| ≤ a and
//! |j| ≤ j hold everywhere on the arc, whatever the profile does within its limits.
inline constexpr double arc_centripetal_acceleration_share = 0.7;
inline constexpr double arc_centripetal_jerk_share = 0.3;
inline constexpr double arc_normal_jerk_share = 0.6;

//! The limits of a segment under the machine's limits: lines get min(F, v_max), a_max, j_max; arcs
//! the split above; dwells zeros.
SegmentLimits segment_limits(const PathSegment& segment, const MotionLimits& limits) noexcept;

}  // namespace stiffpath::motion
