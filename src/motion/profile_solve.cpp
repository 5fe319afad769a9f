// The profile solver: validates the input, picks the peak-speed case and lays out the seven phases.
#include <algorithm>
#include <cmath>

#include "profile_cases.hpp"
#include "stiffpath/motion/profile.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {

namespace {

constexpr double relative_tolerance = 1e-9;

bool finite_non_negative(double x) noexcept { return std::isfinite(x) && x >= 0.0; }
bool finite_positive(double x) noexcept { return std::isfinite(x) && x > 0.0; }

// The highest peak speed in [v_low, v_max] whose two halves fit in the length.
double peak_speed(const ProfileInput& in, double v_low, double v_max) noexcept {
  const double a = in.max_acceleration_m_s2, j = in.max_jerk_m_s3;
  const double v0 = in.start_velocity_m_s, v1 = in.end_velocity_m_s, length = in.length_m;
  if (detail::peak_distance(v_max, v0, v1, a, j) <= length) return v_max;  // cruise at the limit
  const double both_trapezoids = v_low + a * a / j;  // above this, both halves reach a
  if (both_trapezoids < v_max && detail::peak_distance(both_trapezoids, v0, v1, a, j) <= length) {
    return std::clamp(detail::peak_speed_both_trapezoids(length, v0, v1, a, j), both_trapezoids, v_max);
  }
  return detail::peak_speed_numeric(length, v0, v1, a, j, v_low, std::min(both_trapezoids, v_max));
}

}  // namespace

ProfileStatus solve_profile(const ProfileInput& in, Profile& out) noexcept {
  if (!finite_non_negative(in.length_m) || !finite_non_negative(in.start_velocity_m_s) ||
      !finite_non_negative(in.end_velocity_m_s) || !finite_positive(in.max_velocity_m_s) ||
      !finite_positive(in.max_acceleration_m_s2) || !finite_positive(in.max_jerk_m_s3)) {
    return ProfileStatus::invalid_input;
  }
  const double v_low = std::max(in.start_velocity_m_s, in.end_velocity_m_s);
  if (v_low > in.max_velocity_m_s * (1.0 + relative_tolerance)) return ProfileStatus::invalid_input;
  const double a = in.max_acceleration_m_s2, j = in.max_jerk_m_s3;
  // Reachability is judged on speeds, like the planner's passes: when the speed change is a few
  // thousand ulps of the speed, its distance is only known to a few 1e-5 (the speeds are rounded).
  const double v_from = std::min(in.start_velocity_m_s, in.end_velocity_m_s);
  if (v_low > reachable_speed(in.length_m, v_from, a, j) * (1.0 + relative_tolerance) + 1e-15) {
    return ProfileStatus::unreachable;
  }
  const double least_distance = speed_change(in.start_velocity_m_s, in.end_velocity_m_s, a, j).distance_m;

  const double v_max = std::max(in.max_velocity_m_s, v_low);
  const double v_peak = least_distance >= in.length_m ? v_low : peak_speed(in, v_low, v_max);
  const SpeedChange up = speed_change(in.start_velocity_m_s, v_peak, a, j);
  const SpeedChange down = speed_change(v_peak, in.end_velocity_m_s, a, j);
  const double cruise_m = in.length_m - up.distance_m - down.distance_m;

  out.phase_s = {up.ramp_s,   up.plateau_s,   up.ramp_s,
                 v_peak > 0.0 ? std::max(cruise_m, 0.0) / v_peak : 0.0,
                 down.ramp_s, down.plateau_s, down.ramp_s};
  out.jerk_m_s3 = j;
  out.start_velocity_m_s = in.start_velocity_m_s;
  out.peak_velocity_m_s = v_peak;
  out.end_velocity_m_s = in.end_velocity_m_s;
  out.length_m = in.length_m;
  out.duration_s = 0.0;
  for (const double phase : out.phase_s) out.duration_s += phase;
  return ProfileStatus::ok;
}

}  // namespace stiffpath::motion
