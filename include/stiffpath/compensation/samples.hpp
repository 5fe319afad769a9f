// Inputs and outputs of the compensation step: one planned task-space sample in, one joint command out.
#pragma once

#include <cstdint>

#include "stiffpath/kinematics/types.hpp"

namespace stiffpath::compensation {

using kinematics::Mat2;
using kinematics::Vec2;

//! One sample of the planned end-effector trajectory (SI).
struct TaskSample {
  double t_s = 0.0;
  Vec2 position_m = Vec2::Zero();
  Vec2 velocity_m_s = Vec2::Zero();
  Vec2 acceleration_m_s2 = Vec2::Zero();  //!< analytic from the profile, or numeric (thesis route)
  Vec2 jerk_m_s3 = Vec2::Zero();          //!< feeds the commanded velocity's correction term
  Vec2 snap_m_s4 = Vec2::Zero();          //!< d⁴p/dt⁴; zero inside every jerk-limited phase
  Vec2 crackle_m_s5 = Vec2::Zero();       //!< d⁵p/dt⁵ (from the smoothing filters; dynamic compensation only)
  bool laser_on = false;
  double power = 0.0;                     //!< laser power, fraction of full power 0..1 (0 when off)
  int line = 0;                           //!< source G-code line
};

//! Outcome of one step. Anything but ok means: do not send this command, stop the job.
enum class Status : std::uint8_t {
  ok,
  not_finite,          //!< a NaN or infinity in the input sample
  outside_grid,        //!< the compliance model's policy is `error` and p is off its grid
  unreachable,         //!< p_cmd fails the mechanism's singularity margin (see `reach`)
  joint_position,      //!< θ outside the joint's range
  joint_velocity,      //!< |ω| above the joint's limit
  joint_acceleration,  //!< |α| above the joint's limit
};

//! Human-readable name of a status.
const char* describe(Status status) noexcept;

//! The command for one sample. Joint values are only meaningful when status == ok; they are never NaN.
struct JointCommand {
  double t_s = 0.0;
  Vec2 q_rad = Vec2::Zero();           //!< θ1, θ2
  Vec2 qd_rad_s = Vec2::Zero();        //!< ω1, ω2
  Vec2 qdd_rad_s2 = Vec2::Zero();      //!< α1, α2
  Vec2 target_m = Vec2::Zero();        //!< planned point p
  Vec2 command_m = Vec2::Zero();       //!< corrected target p_cmd = p − k·Δ
  Vec2 force_N = Vec2::Zero();         //!< D'Alembert force F = −m·a at the CG
  Vec2 deflection_m = Vec2::Zero();    //!< predicted Δ = model(p, F) (dynamic: the tip's lag −δ)
  Vec2 load_torque_Nm = Vec2::Zero();  //!< Jᵀ·m·a: the tip's load on the drives, for torque feed-forward
  Status status = Status::ok;
  int joint = -1;                      //!< offending joint (0, 1) for joint_* statuses
  bool outside_grid = false;           //!< p was outside the model's grid (clamped or extrapolated)
  bool laser_on = false;
  double power = 0.0;                  //!< laser power, fraction of full power 0..1 (passed through)
  int line = 0;
};

}  // namespace stiffpath::compensation
