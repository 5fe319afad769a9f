// The profile solver: validates the input, picks the peak-speed case and lays out the seven phases.
#include <algorithm>
#include <cmath>

#include "profile_cases.hpp"
#include "stiffpath/motion/profile.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {

namespace detail {

double peak_distance(double v_peak, double v0, double v1, double a, double j) noexcept {
  return speed_change(v0, v_peak, a, j).distance_m + speed_change(v_peak, v1, a, j).distance_m;
}

}  // namespace detail

namespace {

constexpr double relative_tolerance = 1e-9;

bool finite_non_negative(double x) noexcept { return std::isfinite(x) && x >= 0.0; }
bool finite_positive(double x) noexcept { return std::isfinite(x) && x > 0.0; }

// The highest peak speed in (v_low, hi] below the acceleration-limit case: the half from the higher
// end speed is a triangle; the other is a triangle too unless the peak lies above v_lo + a²/j.
double peak_speed_below_acceleration_limit(const ProfileInput& in, double hi) noexcept {
  const double a = in.max_acceleration_m_s2, j = in.max_jerk_m_s3, length = in.length_m;
  const double v_hi = std::max(in.start_velocity_m_s, in.end_velocity_m_s);
  const double v_lo = std::min(in.start_velocity_m_s, in.end_velocity_m_s);
  const double v_lo_trapezoid = v_lo + a * a / j;  // above this peak the half from v_lo reaches a
  const bool trapezoid = v_lo_trapezoid <= v_hi ||
                         (v_lo_trapezoid < hi && detail::peak_distance(v_lo_trapezoid, v_hi, v_lo, a, j) <= length);
  const double v_peak = trapezoid ? detail::peak_speed_triangle_trapezoid(length, v_hi, v_lo, a, j)
                                  : detail::peak_speed_two_triangles(length, v_hi, v_lo, j);
  return std::clamp(v_peak, v_hi, hi);
}

}  // namespace

ProfileStatus solve_profile(const ProfileInput& in, Profile& out) noexcept {
  if (!finite_non_negative(in.length_m) || !finite_non_negative(in.start_velocity_m_s) ||
      !finite_non_negative(in.end_velocity_m_s) || !finite_positive(in.max_velocity_m_s) ||
      !finite_positive(in.max_acceleration_m_s2) || !finite_positive(in.max_jerk_m_s3)) {
    return ProfileStatus::invalid_input;
  }
  const double v0 = in.start_velocity_m_s, v1 = in.end_velocity_m_s, length = in.length_m;
  const double v_low = std::max(v0, v1);
  if (v_low > in.max_velocity_m_s * (1.0 + relative_tolerance)) return ProfileStatus::invalid_input;
  const double a = in.max_acceleration_m_s2, j = in.max_jerk_m_s3;
  const double v_max = std::max(in.max_velocity_m_s, v_low);

  double v_peak = v_low;
  SpeedChange up = speed_change(v0, v1, a, j), down;  // first: the direct change, the least distance
  if (up.distance_m >= length) {
    // Only a monotone change can fit, if any. Reachability is judged on speeds, like the planner's
    // passes: when the speed change is a few thousand ulps of the speed, its distance is only known
    // to a few 1e-5 (the speeds are rounded).
    const double v_from = std::min(v0, v1);
    if (v_low > reachable_speed(length, v_from, a, j) * (1.0 + relative_tolerance) + 1e-15) {
      return ProfileStatus::unreachable;
    }
    up = speed_change(v0, v_low, a, j);
    down = speed_change(v_low, v1, a, j);
  } else {
    up = speed_change(v0, v_max, a, j);
    down = speed_change(v_max, v1, a, j);
    if (up.distance_m + down.distance_m <= length) {
      v_peak = v_max;  // cruise at the limit
    } else {
      const double both_trapezoids = v_low + a * a / j;  // above this, both halves reach a
      if (both_trapezoids < v_max && detail::peak_distance(both_trapezoids, v0, v1, a, j) <= length) {
        v_peak = std::clamp(detail::peak_speed_both_trapezoids(length, v0, v1, a, j), both_trapezoids, v_max);
        up = speed_change(v0, v_peak, a, j);
        down = speed_change(v_peak, v1, a, j);
      } else {
        v_peak = peak_speed_below_acceleration_limit(in, std::min(both_trapezoids, v_max));
        up = speed_change(v0, v_peak, a, j);
        down = speed_change(v_peak, v1, a, j);
        // The quartic's root is exact to a few ulps; rounding may still leave the halves a few ulps
        // of the length too long. Step the peak down until they fit, as the profile computes them.
        for (int step = 0; step < 64 && v_peak > v_low && up.distance_m + down.distance_m > length; ++step) {
          v_peak = std::nextafter(v_peak, v_low);
          up = speed_change(v0, v_peak, a, j);
          down = speed_change(v_peak, v1, a, j);
        }
        if (up.distance_m + down.distance_m > length) {
          v_peak = v_low;
          up = speed_change(v0, v_low, a, j);
          down = speed_change(v_low, v1, a, j);
        }
      }
    }
  }
  const double cruise_m = length - up.distance_m - down.distance_m;

  out.phase_s = {up.ramp_s,   up.plateau_s,   up.ramp_s,
                 v_peak > 0.0 ? std::max(cruise_m, 0.0) / v_peak : 0.0,
                 down.ramp_s, down.plateau_s, down.ramp_s};
  out.jerk_m_s3 = j;
  out.start_velocity_m_s = v0;
  out.peak_velocity_m_s = v_peak;
  out.end_velocity_m_s = v1;
  out.length_m = length;
  out.duration_s = 0.0;
  for (const double phase : out.phase_s) out.duration_s += phase;
  return ProfileStatus::ok;
}

}  // namespace stiffpath::motion
