// Motion-planning flags shared by `plan`, `run` and the simulation commands, and their PlanOptions.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::cli {

struct MotionFlags {
  std::string accel = "5g";
  std::optional<double> jerk_m_s3;
  double max_velocity_mm_s = 0.0;  // set from motion's default in add_motion_flags
  double rate_hz = motion::default_sample_rate_hz;
  std::vector<double> work_offset_mm;
  std::vector<double> start_mm;
  double blend_tolerance_mm = 0.01;
  double junction_time_ms = 0.5;
  std::size_t lookahead = 0;
};

//! Registers --accel, --jerk, --max-velocity-mm-s, --rate, --work-offset-mm, --start-mm,
//! --blend-tolerance-mm, --junction-time-ms and --lookahead on `cmd`.
void add_motion_flags(CLI::App* cmd, MotionFlags& flags);
//! The planner's options from the flags (throws stiffpath::Error for a bad --accel).
motion::PlanOptions plan_options(const MotionFlags& flags);

}  // namespace stiffpath::cli
