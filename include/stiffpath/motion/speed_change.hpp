// Jerk-limited speed change with zero acceleration at both ends: its duration and distance, and its inverse.
#pragma once

namespace stiffpath::motion {

//! One monotone speed change from v_from to v_to (either direction) that starts and ends with zero
//! acceleration, as fast as the limits allow: jerk ±j for the ramps and, when |Δv| > a²/j, a plateau
//! at ±a (a trapezoid of acceleration); otherwise a triangle peaking at sqrt(|Δv|·j).
struct SpeedChange {
  double ramp_s = 0.0;                //!< duration of each jerk ramp (s)
  double plateau_s = 0.0;             //!< duration of the constant-acceleration plateau (s)
  double duration_s = 0.0;            //!< 2·ramp + plateau (s)
  double distance_m = 0.0;            //!< (v_from + v_to)/2 · duration: the acceleration is symmetric in time
  double peak_acceleration_m_s2 = 0.0;
};

//! The fastest speed change between two speeds under |a| ≤ a and |j| ≤ j (both > 0).
SpeedChange speed_change(double v_from_m_s, double v_to_m_s, double max_acceleration_m_s2,
                         double max_jerk_m_s3) noexcept;

//! The highest speed v ≥ v_from such that speed_change(v_from, v).distance_m ≤ length_m: how fast the
//! path can be at the end of a segment entered at v_from (forward pass), or equally how fast it may be
//! at the start of a segment that must end at v_from (backward pass). Closed form: a cubic in
//! sqrt(Δv/j) (triangle) or a quadratic in Δv (trapezoid). Not capped by any velocity limit.
double reachable_speed(double length_m, double v_from_m_s, double max_acceleration_m_s2,
                       double max_jerk_m_s3) noexcept;

//! The highest speed at which a segment of length L may be entered so that it can be left at some
//! speed in [0, exit_max] (the backward pass). Note that braking to rest can take less distance
//! than braking part of the way: the distance (v_lo + v_hi)/2 · T(v_hi − v_lo) first rises, then
//! falls as v_lo goes from 0 to v_hi. So the answer is max(reachable(L, 0), reachable(L, exit_max)).
double max_entry_speed(double length_m, double exit_max_m_s, double max_acceleration_m_s2,
                       double max_jerk_m_s3) noexcept;

//! The highest exit speed in [0, exit_max] that a segment of length L entered at `entry` can reach
//! (the forward pass), for an entry admitted by max_entry_speed. Usually min(exit_max,
//! reachable(L, entry)); when that would mean braking part of the way over more than L, the
//! largest lower exit that fits (found by bisection on the rising branch of the distance).
double max_exit_speed(double length_m, double entry_m_s, double exit_max_m_s, double max_acceleration_m_s2,
                      double max_jerk_m_s3) noexcept;

//! The speed `distance_m` after the start of the fastest speed-up from v0 at zero acceleration (jerk
//! j until the acceleration reaches a, then a), not capped by any velocity limit. No profile of the
//! planner that starts at v0 with zero acceleration is faster at that distance: along a speed-up
//! the acceleration at each speed is at most the fastest one's (a² ≤ 2·j·(v − v0), a ≤ a_max), so
//! each speed is reached no sooner in distance, and after the peak the speed only falls. By time
//! reversal the same bound holds counted back from the profile's end at its exit speed. Within
//! the jerk ramp the time is solved from above, so the bound rounds up there; past it, a closed form.
double fastest_speed_up(double distance_m, double v0_m_s, double max_acceleration_m_s2, double max_jerk_m_s3) noexcept;

}  // namespace stiffpath::motion
