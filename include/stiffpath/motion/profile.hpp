// Time-optimal jerk-limited (7-phase, trapezoidal acceleration) speed profile along one segment.
#pragma once

#include <array>
#include <cstdint>

namespace stiffpath::motion {

//! What one segment's profile must do (Ruckig-style input). Speeds are along the path.
struct ProfileInput {
  double length_m = 0.0;              //!< distance to travel (m), ≥ 0
  double start_velocity_m_s = 0.0;    //!< speed at the start (m/s), ≥ 0, acceleration 0 there
  double end_velocity_m_s = 0.0;      //!< speed at the end (m/s), ≥ 0, acceleration 0 there
  double max_velocity_m_s = 0.0;      //!< speed limit along the segment (m/s), > 0
  double max_acceleration_m_s2 = 0.0; //!< tangential acceleration limit (m/s²), > 0
  double max_jerk_m_s3 = 0.0;         //!< tangential jerk limit (m/s³), > 0
};

enum class ProfileStatus : std::uint8_t {
  ok,
  invalid_input,  //!< a negative or non-finite value, a speed above max_velocity, or a limit ≤ 0
  unreachable,    //!< the speed change between start and end needs more than length_m
};

//! "ok", "invalid input", "end speed unreachable within the length".
const char* describe(ProfileStatus status) noexcept;

//! Path state along a profile at one instant: arc length, speed, tangential acceleration and jerk.
struct ProfileState {
  double s_m = 0.0;
  double v_m_s = 0.0;
  double a_m_s2 = 0.0;
  double j_m_s3 = 0.0;
};

//! A 7-phase profile: jerk +j, 0, −j (acceleration to the peak speed), cruise at the peak speed,
//! jerk −j, 0, +j (deceleration to the end speed). Either half may be empty (only acceleration or
//! only deceleration), the cruise is empty when the peak is below the speed limit, and the plateaus
//! are empty when the acceleration limit is not reached. Thesis §4.3, fig. 4.3.
struct Profile {
  std::array<double, 7> phase_s{};    //!< durations of the seven phases (s)
  double jerk_m_s3 = 0.0;             //!< magnitude of the jerk in the ramp phases (m/s³)
  double start_velocity_m_s = 0.0;
  double peak_velocity_m_s = 0.0;     //!< speed during the cruise phase (m/s)
  double end_velocity_m_s = 0.0;
  double length_m = 0.0;
  double duration_s = 0.0;            //!< sum of the phases (s)

  //! State at time t from the start; t ≤ 0 gives the start, t ≥ duration gives exactly
  //! (length, end velocity, 0, 0). The deceleration half is evaluated backwards from the end so
  //! that the end state is exact. Jerk is the one of the phase that contains t (left-closed).
  [[nodiscard]] ProfileState state_at(double t_s) const noexcept;

  //! The instant at which the profile has covered s_m, the inverse of state_at's arc length (which
  //! never falls): Newton's method on s(t) − s_m, safeguarded by bisection. s ≤ 0 gives 0, s ≥ length
  //! the duration.
  [[nodiscard]] double time_at(double s_m) const noexcept;
};

//! The time-optimal profile for the input: the highest peak speed whose acceleration and
//! deceleration fit in the length (cruising at the limit when it is reached). Returns the status;
//! `out` is written only when the status is ok. Never throws, never allocates.
ProfileStatus solve_profile(const ProfileInput& input, Profile& out) noexcept;

}  // namespace stiffpath::motion
