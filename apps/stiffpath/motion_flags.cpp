// Motion-planning flags shared by the subcommands that plan G-code, checked against their documented ranges.
#include "motion_flags.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <fmt/format.h>

#include "commands.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::cli {

namespace {

constexpr double max_offset_mm = motion::max_coordinate_m * 1e3;

void check(const char* flag, double value, double low, double high, const char* unit) {
  if (!(value >= low && value <= high)) {  // NaN fails too
    throw Error(fmt::format("{}: must be within [{:g}, {:g}]{}{}, got {}", flag, low, high, *unit ? " " : "", unit, value));
  }
}

std::optional<motion::Vec2> point_mm(const char* flag, const std::vector<double>& xy) {
  if (xy.empty()) return std::nullopt;
  for (const double v : xy) check(flag, v, -max_offset_mm, max_offset_mm, "mm");
  return motion::Vec2(units::mm_to_m(xy[0]), units::mm_to_m(xy[1]));
}

std::optional<double> stop_dwell_s(const std::string& text) {
  if (text == "pause") return std::nullopt;
  double seconds = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seconds);
  if (ec != std::errc() || end != text.data() + text.size()) {
    throw Error(fmt::format("--program-stop: 'pause' or a dwell in seconds, got '{}'", text));
  }
  check("--program-stop", seconds, 0.0, motion::max_block_duration_s, "s");
  return seconds;
}

}  // namespace

void add_motion_flags(CLI::App* cmd, MotionFlags& a) {
  enable_json_errors(cmd);  // a program's refusals are many: with --json they are one document
  a.max_velocity_mm_s = units::m_to_mm(motion::default_max_velocity_m_s);
  cmd->add_option("--accel", a.accel, "Acceleration limit, e.g. 5g or 49 (m/s^2)")->capture_default_str();
  cmd->add_option("--jerk", a.jerk, "Jerk limit (m/s^3); default: accel / 5 ms; run: auto = accel x the tip's lowest "
                                   "natural frequency on the job");
  cmd->add_option("--max-velocity-mm-s", a.max_velocity_mm_s, "Speed limit, also of G0 (mm/s)")->capture_default_str();
  cmd->add_option("--rate", a.rate_hz, "Sampling rate (Hz)")->capture_default_str();
  cmd->add_option("--work-offset-mm", a.work_offset_mm, "G54 origin in the robot frame: X,Y (mm)")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--start-mm", a.start_mm, "Where the robot starts: X,Y (mm); default: the first move's target")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--blend-tolerance-mm", a.blend_tolerance_mm, "Corner tolerance of a G64 without P (mm)")
      ->capture_default_str();
  cmd->add_option("--chords", a.chords,
                  "G64 chains of short lines: blend (a fillet at each vertex) or fit (one smooth curve within P)")
      ->check(CLI::IsMember({"blend", "fit"}))
      ->capture_default_str();
  cmd->add_option("--junction-time-ms", a.junction_time_ms, "Junction time: steps of v and a allowed at joins (ms)")
      ->capture_default_str();
  cmd->add_option("--lookahead", a.lookahead, "Look-ahead bound in segments (0: whole program)")->capture_default_str();
  cmd->add_flag("--strict", a.strict,
                "Refuse Z, T/M6, O, G28/G30, G91.1, M0/M1, M106/M107, M62/M63, block delete, BOM, EOF char, nested comments");
  cmd->add_option("--dwell-p-units", a.dwell_p_units, "Units of G4 P: s (LinuxCNC, GRBL) or ms (Marlin)")
      ->check(CLI::IsMember({"s", "ms"}))
      ->capture_default_str();
  cmd->add_option("--s-max", a.s_max, "S of full laser power (GRBL $30: 1000; Marlin: 255)")->capture_default_str();
  cmd->add_option("--program-stop", a.program_stop, "M0/M1: pause (rest, go on at once) or a dwell in seconds")
      ->capture_default_str();
  cmd->add_option("--block-delete", a.block_delete, "Lines starting with '/': run or skip")
      ->check(CLI::IsMember({"run", "skip"}))
      ->capture_default_str();
}

motion::PlanOptions plan_options(const MotionFlags& a, const kinematics::Robot& robot) {
  motion::PlanOptions o;
  o.gcode.home_position_m = robot.home_m;  // G28 goes to the robot file's home_mm
  try {
    o.limits.max_acceleration_m_s2 = units::parse_acceleration_m_s2(a.accel);
  } catch (const Error& e) {
    throw Error(std::string("--accel: ") + e.what());
  }
  check("--accel", o.limits.max_acceleration_m_s2, motion::min_acceleration_limit_m_s2,
        motion::max_acceleration_limit_m_s2, "m/s^2");
  std::optional<double> jerk = a.jerk_m_s3;
  if (!jerk && !a.jerk.empty()) {
    if (a.jerk == "auto") throw Error("--jerk auto: only `stiffpath run` knows the tip's natural frequency");
    try {
      std::size_t used = 0;
      jerk = std::stod(a.jerk, &used);
      if (used != a.jerk.size()) throw std::invalid_argument("trailing text");
    } catch (const std::exception&) {
      throw Error("--jerk: expected a number (m/s^3) or auto, got '" + a.jerk + "'");
    }
  }
  o.limits.max_jerk_m_s3 = jerk.value_or(motion::default_jerk_m_s3(o.limits.max_acceleration_m_s2));
  check("--jerk", o.limits.max_jerk_m_s3, motion::min_jerk_limit_m_s3, motion::max_jerk_limit_m_s3, "m/s^3");
  check("--max-velocity-mm-s", a.max_velocity_mm_s, units::m_to_mm(motion::min_velocity_limit_m_s),
        units::m_to_mm(motion::max_velocity_limit_m_s), "mm/s");
  o.limits.max_velocity_m_s = units::mm_to_m(a.max_velocity_mm_s);
  check("--rate", a.rate_hz, 1.0, 1e5, "Hz");
  o.rate_hz = a.rate_hz;
  if (const auto offset = point_mm("--work-offset-mm", a.work_offset_mm)) o.gcode.work_offset_m = *offset;
  o.gcode.start_position_m = point_mm("--start-mm", a.start_mm);
  check("--blend-tolerance-mm", a.blend_tolerance_mm, 0.0, motion::max_blend_tolerance_m * 1e3, "mm");
  o.gcode.default_blend_tolerance_m = units::mm_to_m(a.blend_tolerance_mm);
  check("--junction-time-ms", a.junction_time_ms, 0.0, 1000.0, "ms");
  o.planner.junction.junction_time_s = a.junction_time_ms * 1e-3;
  o.planner.junction.fit_chords = a.chords == "fit";
  o.planner.max_lookahead_segments = a.lookahead;
  o.gcode.strict = a.strict;
  o.gcode.dwell_p_units = a.dwell_p_units == "ms" ? motion::DwellUnits::milliseconds : motion::DwellUnits::seconds;
  check("--s-max", a.s_max, 1e-6, 1e9, "");
  o.gcode.s_max = a.s_max;
  o.gcode.program_stop_dwell_s = stop_dwell_s(a.program_stop);
  o.gcode.skip_block_delete = a.block_delete == "skip";
  o.gcode.on_warnings = print_gcode_warnings;
  return o;
}

void print_gcode_warnings(const std::string& file, const std::vector<motion::GcodeWarning>& warnings) {
  for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", motion::describe(w, file).c_str());
}

}  // namespace stiffpath::cli
