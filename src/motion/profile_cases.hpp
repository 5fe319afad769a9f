// Internal: the peak-speed cases of the profile solver (one file each) and the piece evaluator they share.
#pragma once

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

//! Peak-speed case "at least one half is a triangle (acceleration limit not reached)": safeguarded
//! Newton on the monotone distance in [lo, hi] (profile_peak_numeric.cpp). Returns the largest
//! peak speed found whose distance does not exceed length_m.
double peak_speed_numeric(double length_m, double v0, double v1, double a, double j, double lo,
                          double hi) noexcept;

}  // namespace stiffpath::motion::detail
