// Shared small types of the kinematics module: planar vectors, reach status, singularity margin.
#pragma once

#include <Eigen/Core>

namespace stiffpath::kinematics {

using Vec2 = Eigen::Vector2d;  //!< task space (x, y) in m, or joint space (θ1, θ2) in rad
using Mat2 = Eigen::Matrix2d;

//! Why a task-space point can or cannot be used. Returned by the noexcept paths (real-time use).
enum class Reach {
  ok,
  not_finite,       //!< the point has a NaN or infinite coordinate
  near_stretched,   //!< r > 2l − margin: the arms are (almost) fully stretched (boundary singularity)
  near_origin,      //!< r < margin: the platform is (almost) at the actuator axis (r → 0)
  ill_conditioned,  //!< the Jacobian's condition number exceeds the margin's maximum
};

//! Human-readable reason for a Reach value.
const char* describe(Reach reach) noexcept;

//! How far from a singularity a point must stay. Documented defaults, see docs/kinematics.md.
struct SingularityMargin {
  double min_distance_m = 0.005;       //!< minimum distance of r from 2l and from 0 (m)
  double max_condition_number = 8.0;   //!< maximum 2-norm condition number of J (dimensionless)
};

}  // namespace stiffpath::kinematics
