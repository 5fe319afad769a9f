// Eq. 2.3 (G from U and L) and the replica's tilt angles.
#include "stiffpath/measurement/platform_pose.hpp"

#include <cmath>

namespace stiffpath::measurement {

Vec3 cg_point(const Vec3& U, const Vec3& L, const ReplicaGeometry& geometry) noexcept {
  return U + (geometry.ug_m / geometry.ul_m) * (L - U);
}

Tilt tilt(const Vec3& U, const Vec3& L) noexcept {
  const Vec3 a = U - L;
  return {std::atan2(-a.y(), a.z()), std::atan2(a.x(), a.z())};
}

Vec3 axis_from_tilt(const Tilt& t) noexcept {
  return Vec3(std::tan(t.ry_rad), -std::tan(t.rx_rad), 1.0).normalized();
}

}  // namespace stiffpath::measurement
