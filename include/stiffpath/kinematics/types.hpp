// Shared small types of the kinematics module: planar vectors, reach status, singularity margin.
#pragma once

#include <Eigen/Core>

namespace stiffpath::kinematics {

using Vec2 = Eigen::Vector2d;  //!< task space (x, y) in m, or joint space (θ1, θ2) in rad
using Mat2 = Eigen::Matrix2d;

//! Why a task-space point can or cannot be used. Returned by the noexcept paths (real-time use).
//! Serial singularities (an arm stretched out or folded) make J lose rank; the parallel one (the
//! distal links collinear) makes the platform lose its stiffness against one direction of force.
enum class Reach {
  ok,
  not_finite,       //!< the point has a NaN or infinite coordinate
  near_stretched,   //!< |A_i C| > l_p + l_d − margin: an arm is (almost) stretched out (serial singularity)
  near_origin,      //!< |A_i C| < |l_p − l_d| + margin: an arm is (almost) folded (serial; r → 0 for the thesis)
  near_parallel,    //!< the distal links are (almost) collinear (parallel singularity)
  other_assembly,   //!< reachable only in the other assembly mode: across the parallel singularity
  ill_conditioned,  //!< the Jacobian's condition number exceeds the margin's maximum
};

//! Human-readable reason for a Reach value.
const char* describe(Reach reach) noexcept;

//! How far from a singularity a point must stay. Documented defaults, see docs/kinematics.md.
struct SingularityMargin {
  double min_distance_m = 0.005;       //!< minimum distance of |A_i C| from l_p + l_d and from |l_p − l_d| (m)
  double max_condition_number = 8.0;   //!< maximum 2-norm condition number of J (dimensionless)
  //! Minimum angle between the distal links (and between them and a straight angle), rad: 10°.
  double min_distal_angle_rad = 0.17453292519943295;
};

}  // namespace stiffpath::kinematics
