// Motion-planning flags shared by `plan`, `run` and the simulation commands, and their PlanOptions.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::cli {

struct MotionFlags {
  std::string accel = "5g";
  std::string jerk;                  // m/s^3, empty: accel / 5 ms, "auto": from the tip (run resolves it)
  std::optional<double> jerk_m_s3;   // the number --jerk gave, or the one `run` chose for "auto"
  double max_velocity_mm_s = 0.0;  // set from motion's default in add_motion_flags
  double rate_hz = motion::default_sample_rate_hz;
  std::string work_offset_mm;       // "X,Y"; empty: 0,0
  std::string start_mm;             // "X,Y"; empty: the first move's target
  std::string blend = "on";         // a program without G61/G64: on (blend within the tolerance) or off
  double blend_tolerance_mm = motion::default_blend_tolerance_m * 1e3;
  std::string chords = "auto";   // G64 chains of short lines: blend (a fillet each), fit, or auto (fit merged ones)
  double junction_time_ms = 0.5;
  std::size_t lookahead = 0;
  bool strict = false;
  std::string dwell_p_units = "s";
  double s_max = motion::default_s_max;
  std::string program_stop = "pause";
  std::string block_delete = "run";
  std::string ignore_m = "M100,M17,M18,M52,M65,M67,M68";  // vendor M-codes ignored with a warning; "none"
  std::string outputs;              // what M62/M63 P<n> and M106/M107 P<n> drive: "P0=ignore,fan1=laser"
};

//! Registers --accel, --jerk, --max-velocity-mm-s, --rate, --work-offset-mm, --start-mm, --blend,
//! --blend-tolerance-mm, --chords, --junction-time-ms, --lookahead and the dialect flags --strict,
//! --dwell-p-units, --s-max, --program-stop, --block-delete, --ignore-m and --outputs on `cmd`. Every
//! option takes exactly one word ("X,Y" as one), so none swallows the job's name after it.
void add_motion_flags(CLI::App* cmd, MotionFlags& flags);
//! The planner's options from the flags. Every number is checked against its documented range
//! (docs/motion.md); a bad one throws stiffpath::Error "--flag: reason, got value". The G-code
//! warnings are printed to stderr, one line per kind, when the program has been read.
motion::PlanOptions plan_options(const MotionFlags& flags, const kinematics::Robot& robot);
//! Prints the summarised warnings as "warning: file:line: message" lines on stderr.
void print_gcode_warnings(const std::string& file, const std::vector<motion::GcodeWarning>& warnings);
//! The account of lost time (SlowdownReport) as summary lines: planned against programmed time,
//! the time each limit cost, and the slowest stretches with their G-code lines.
void print_slowdowns(std::FILE* out, const motion::SlowdownReport& report);
//! The same as JSON: {"programmed_time_s", "planned_time_s", "feed_above_limit_s", "shortcut_s", "lost_s": {limit: s},
//! "stretches": [{"first_line", "last_line", "start_s", "duration_s", "programmed_s", "lost_s",
//! "lowest_speed_m_s", "limits": {limit: s}}]}.
nlohmann::json slowdowns_json(const motion::SlowdownReport& report);

}  // namespace stiffpath::cli
