// Eq. 2.3: the CG point G and the tilt of the measurement replica from the two measured points U and L.
#pragma once

#include <Eigen/Core>

namespace stiffpath::measurement {

using Vec3 = Eigen::Vector3d;  //!< a point or vector in the CMM frame (m), aligned with the robot frame

//! Geometry of the laser-head replica (fig. 2.4): U is the upper and L the lower measured point on the
//! replica's axis, G the platform's CG point between them.
struct ReplicaGeometry {
  double ug_m = 0.0;  //!< |UG| (fig. 2.4), the robot's (kinematics::Robot::replica)
  double ul_m = 0.0;  //!< |UL| (fig. 2.4); must exceed 0
};

//! Eq. 2.3: G = U + (|UG|/|UL|)·UL with UL = L − U.
Vec3 cg_point(const Vec3& U, const Vec3& L, const ReplicaGeometry& geometry) noexcept;

//! Tilt of the replica's axis a = (U − L)/|U − L| (pointing up, +z when the platform is level), as the
//! two angles of a right-handed rotation about x then y that takes +z onto a:
//! rx = atan2(−a_y, a_z), ry = atan2(a_x, a_z) (rad). With this parametrisation a ∝ (tan ry, −tan rx, 1),
//! so the angular deflection of a load step is the plain difference of the angles to those of step 0.
struct Tilt {
  double rx_rad = 0.0;  //!< about the x axis
  double ry_rad = 0.0;  //!< about the y axis
};
Tilt tilt(const Vec3& U, const Vec3& L) noexcept;

//! Inverse of tilt(): the unit axis (U − L)/|U − L| of a replica tilted by (rx, ry).
Vec3 axis_from_tilt(const Tilt& t) noexcept;

}  // namespace stiffpath::measurement
