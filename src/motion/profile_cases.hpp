// Internal: the peak-speed cases of the profile solver (one file each) and the helpers they share.
#pragma once

#include <limits>

#include "stiffpath/motion/profile.hpp"

namespace stiffpath::motion::detail {

//! State after tau seconds of a speed-up piece from v_from (jerk +j for `ramp_s`, 0 for `plateau_s`,
//! −j for `ramp_s`); tau past the end gives the end state with zero acceleration and jerk.
ProfileState speed_up_state(double v_from_m_s, double ramp_s, double plateau_s, double jerk_m_s3,
                            double tau_s) noexcept;

//! Distance of accelerating from each end speed to v_peak and back: f(v_peak) + length, monotone.
double peak_distance(double v_peak, double v0, double v1, double a, double j) noexcept;

//! Peak-speed case "both halves reach the acceleration limit, no cruise": the root of a quadratic
//! (profile_peak_trapezoid.cpp). Valid when the root is ≥ max(v0, v1) + a²/j.
double peak_speed_both_trapezoids(double length_m, double v0, double v1, double a, double j) noexcept;

//! Peak-speed case "neither half reaches the acceleration limit, no cruise": a quartic in the
//! duration (profile_peak_two_triangles.cpp). v_hi ≥ v_lo are the two end speeds.
double peak_speed_two_triangles(double length_m, double v_hi, double v_lo, double j) noexcept;

//! Peak-speed case "the half from the higher end speed v_hi is a triangle, the other reaches the
//! acceleration limit, no cruise": a quartic in the triangle's ramp time
//! (profile_peak_triangle_trapezoid.cpp).
double peak_speed_triangle_trapezoid(double length_m, double v_hi, double v_lo, double a, double j) noexcept;

//! The positive root of c4·x⁴ + c3·x³ + c2·x² + c1·x + c0 by Newton's method from x0 above it,
//! for a quartic that is increasing and convex from its root up to x0: the iterates then fall
//! monotonically onto the root, converging quadratically. Stops at the first step below a few
//! ulps of x or when rounding puts the value at or below zero.
inline double descend_to_root(double c4, double c3, double c2, double c1, double c0, double x0) noexcept {
  double x = x0;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double f = (((c4 * x + c3) * x + c2) * x + c1) * x + c0;
    if (!(f > 0.0)) break;
    const double slope = ((4.0 * c4 * x + 3.0 * c3) * x + 2.0 * c2) * x + c1;
    const double step = f / slope;
    if (!(step > 0.0)) break;
    x -= step;
    if (step <= 4.0 * std::numeric_limits<double>::epsilon() * x) break;
  }
  return x;
}

}  // namespace stiffpath::motion::detail
