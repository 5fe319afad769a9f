// Motion-planning flags shared by the subcommands that plan G-code.
#include "motion_flags.hpp"

#include "stiffpath/core/units.hpp"

namespace stiffpath::cli {

void add_motion_flags(CLI::App* cmd, MotionFlags& a) {
  a.max_velocity_mm_s = units::m_to_mm(motion::default_max_velocity_m_s);
  cmd->add_option("--accel", a.accel, "Acceleration limit, e.g. 5g or 49 (m/s^2)")->capture_default_str();
  cmd->add_option("--jerk", a.jerk_m_s3, "Jerk limit (m/s^3); default: accel / 5 ms")->check(CLI::PositiveNumber);
  cmd->add_option("--max-velocity-mm-s", a.max_velocity_mm_s, "Speed limit, also of G0 (mm/s)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--rate", a.rate_hz, "Sampling rate (Hz)")->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--work-offset-mm", a.work_offset_mm, "G54 origin in the robot frame: X,Y (mm)")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--start-mm", a.start_mm, "Where the robot starts: X,Y (mm); default: the first move's target")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--blend-tolerance-mm", a.blend_tolerance_mm, "Corner tolerance of a G64 without P (mm)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--junction-time-ms", a.junction_time_ms, "Junction time: steps of v and a allowed at joins (ms)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--lookahead", a.lookahead, "Look-ahead bound in segments (0: whole program)")->capture_default_str();
}

motion::PlanOptions plan_options(const MotionFlags& a) {
  motion::PlanOptions o;
  o.limits.max_acceleration_m_s2 = units::parse_acceleration_m_s2(a.accel);
  o.limits.max_jerk_m_s3 = a.jerk_m_s3.value_or(motion::default_jerk_m_s3(o.limits.max_acceleration_m_s2));
  o.limits.max_velocity_m_s = units::mm_to_m(a.max_velocity_mm_s);
  o.rate_hz = a.rate_hz;
  if (!a.work_offset_mm.empty()) {
    o.gcode.work_offset_m = {units::mm_to_m(a.work_offset_mm[0]), units::mm_to_m(a.work_offset_mm[1])};
  }
  if (!a.start_mm.empty()) {
    o.gcode.start_position_m = motion::Vec2(units::mm_to_m(a.start_mm[0]), units::mm_to_m(a.start_mm[1]));
  }
  o.gcode.default_blend_tolerance_m = units::mm_to_m(a.blend_tolerance_mm);
  o.planner.junction.junction_time_s = a.junction_time_ms * 1e-3;
  o.planner.max_lookahead_segments = a.lookahead;
  return o;
}

}  // namespace stiffpath::cli
