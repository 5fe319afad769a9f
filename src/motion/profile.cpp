// Evaluation of a 7-phase jerk-limited profile: the speed-up half forwards, the slow-down half backwards from the end.
#include "stiffpath/motion/profile.hpp"

#include <cmath>
#include <limits>

#include "profile_cases.hpp"

namespace stiffpath::motion {

const char* describe(ProfileStatus status) noexcept {
  switch (status) {
    case ProfileStatus::ok: return "ok";
    case ProfileStatus::invalid_input: return "invalid input";
    case ProfileStatus::unreachable: return "end speed unreachable within the length";
  }
  return "unknown";
}

namespace detail {

ProfileState speed_up_state(double v_from_m_s, double ramp_s, double plateau_s, double jerk_m_s3,
                            double tau_s) noexcept {
  const double j = jerk_m_s3, v0 = v_from_m_s;
  if (tau_s < ramp_s) {  // jerk +j
    const double t = tau_s;
    return {v0 * t + j * t * t * t / 6.0, v0 + 0.5 * j * t * t, j * t, j};
  }
  const double peak_a = j * ramp_s;
  const double v1 = v0 + 0.5 * j * ramp_s * ramp_s;
  const double s1 = v0 * ramp_s + j * ramp_s * ramp_s * ramp_s / 6.0;
  if (tau_s < ramp_s + plateau_s) {  // constant acceleration
    const double t = tau_s - ramp_s;
    return {s1 + v1 * t + 0.5 * peak_a * t * t, v1 + peak_a * t, peak_a, 0.0};
  }
  const double v2 = v1 + peak_a * plateau_s;
  const double s2 = s1 + v1 * plateau_s + 0.5 * peak_a * plateau_s * plateau_s;
  const bool past_end = tau_s >= 2.0 * ramp_s + plateau_s;
  const double t = past_end ? ramp_s : tau_s - ramp_s - plateau_s;  // jerk −j
  const ProfileState state{s2 + v2 * t + 0.5 * peak_a * t * t - j * t * t * t / 6.0,
                           v2 + peak_a * t - 0.5 * j * t * t, peak_a - j * t, -j};
  if (past_end) return {state.s_m, state.v_m_s, 0.0, 0.0};
  return state;
}

}  // namespace detail

ProfileState Profile::state_at(double t_s) const noexcept {
  if (!(t_s > 0.0)) {  // the exact start state (also for NaN); jerk of the first non-empty phase
    constexpr double sign[7] = {1.0, 0.0, -1.0, 0.0, -1.0, 0.0, 1.0};
    for (int k = 0; k < 7; ++k) {
      if (phase_s[k] > 0.0) return {0.0, start_velocity_m_s, 0.0, sign[k] * jerk_m_s3};
    }
    return {0.0, start_velocity_m_s, 0.0, 0.0};
  }
  if (t_s >= duration_s) return {length_m, end_velocity_m_s, 0.0, 0.0};
  const double speed_up_s = phase_s[0] + phase_s[1] + phase_s[2];
  if (t_s < speed_up_s) return detail::speed_up_state(start_velocity_m_s, phase_s[0], phase_s[1], jerk_m_s3, t_s);
  if (t_s < speed_up_s + phase_s[3]) {
    const ProfileState top =
        detail::speed_up_state(start_velocity_m_s, phase_s[0], phase_s[1], jerk_m_s3, speed_up_s);
    return {top.s_m + peak_velocity_m_s * (t_s - speed_up_s), peak_velocity_m_s, 0.0, 0.0};
  }
  // Slow-down half, mirrored in time: a speed-up from the end speed with the phases reversed.
  const ProfileState back = detail::speed_up_state(end_velocity_m_s, phase_s[6], phase_s[5], jerk_m_s3,
                                                   duration_s - t_s);
  return {length_m - back.s_m, back.v_m_s, -back.a_m_s2, back.j_m_s3};
}

double Profile::time_at(double s_m) const noexcept {
  if (!(s_m > 0.0)) return 0.0;
  if (s_m >= length_m) return duration_s;
  // In the cruise phase s is linear in t: the time follows directly.
  const double cruise_start_s = phase_s[0] + phase_s[1] + phase_s[2];
  if (phase_s[3] > 0.0 && peak_velocity_m_s > 0.0) {
    const double cruise_start_m = state_at(cruise_start_s).s_m;
    const double into_m = s_m - cruise_start_m;
    if (into_m >= 0.0 && into_m <= peak_velocity_m_s * phase_s[3]) {
      return std::min(cruise_start_s + into_m / peak_velocity_m_s, duration_s);
    }
  }
  double lo = 0.0, hi = duration_s, t = duration_s * (s_m / length_m);
  double step = hi - lo, previous_step = step;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const ProfileState state = state_at(t);
    const double error = state.s_m - s_m;
    if (error == 0.0) return t;
    (error < 0.0 ? lo : hi) = t;
    // Newton while it stays in the bracket and at least halves the step every other iteration
    // (from rest s grows like t³ and Newton creeps); bisection otherwise.
    const double newton = state.v_m_s > 0.0 ? t - error / state.v_m_s : lo - 1.0;
    const bool use_newton = newton > lo && newton < hi && std::abs(2.0 * error) <= std::abs(previous_step * state.v_m_s);
    previous_step = step;
    step = use_newton ? t - newton : 0.5 * (hi - lo);
    t = use_newton ? newton : lo + step;
    if (std::abs(step) <= 4.0 * std::numeric_limits<double>::epsilon() * hi) break;
  }
  return t;
}

}  // namespace stiffpath::motion
