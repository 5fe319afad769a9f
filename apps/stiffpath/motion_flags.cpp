// Motion-planning flags shared by the subcommands that plan G-code, checked against their documented ranges.
#include "motion_flags.hpp"

#include <algorithm>
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

// The comma-separated words of one option value ("a,b,c"); empty words are refused.
std::vector<std::string> words_of(const char* flag, const std::string& text) {
  std::vector<std::string> words;
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = text.find(',', from);
    words.push_back(text.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
    if (words.back().empty()) throw Error(fmt::format("{}: an empty item in '{}'", flag, text));
    if (comma == std::string::npos) return words;
    from = comma + 1;
  }
}

double number_of(const char* flag, const std::string& word, const std::string& whole) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (ec != std::errc() || end != word.data() + word.size()) {
    throw Error(fmt::format("{}: expected a number, got '{}' in '{}'", flag, word, whole));
  }
  return value;
}

// "X,Y" in mm: one word, so that the option never takes the job's name after it.
std::optional<motion::Vec2> point_mm(const char* flag, const std::string& text) {
  if (text.empty()) return std::nullopt;
  const std::vector<std::string> xy = words_of(flag, text);
  if (xy.size() != 2) throw Error(fmt::format("{}: expected X,Y in mm (one word, e.g. 222.132,0), got '{}'", flag, text));
  const double x = number_of(flag, xy[0], text), y = number_of(flag, xy[1], text);
  for (const double v : {x, y}) check(flag, v, -max_offset_mm, max_offset_mm, "mm");
  return motion::Vec2(units::mm_to_m(x), units::mm_to_m(y));
}

// "M100,M17,…" (the M optional), or "none".
std::vector<double> m_codes(const std::string& text) {
  std::vector<double> codes;
  if (text == "none") return codes;
  for (std::string word : words_of("--ignore-m", text)) {
    if (word[0] == 'M' || word[0] == 'm') word.erase(0, 1);
    const double code = number_of("--ignore-m", word, text);
    check("--ignore-m", code, 0.0, motion::max_code_number, "");
    codes.push_back(code);
  }
  return codes;
}

// "P0=ignore,fan1=laser": M62/M63 outputs P<n>, Marlin's fans fan<n>; roles laser or ignore.
std::vector<motion::OutputAssignment> outputs_of(const std::string& text) {
  std::vector<motion::OutputAssignment> outputs;
  if (text.empty()) return outputs;
  for (const std::string& word : words_of("--outputs", text)) {
    const std::size_t equals = word.find('=');
    const std::string port = word.substr(0, equals), role = equals == std::string::npos ? "" : word.substr(equals + 1);
    motion::OutputAssignment output;
    std::string number;
    if (port.size() > 1 && (port[0] == 'P' || port[0] == 'p')) {
      output.kind = motion::OutputKind::digital;
      number = port.substr(1);
    } else if (port.rfind("fan", 0) == 0 && port.size() > 3) {
      output.kind = motion::OutputKind::fan;
      number = port.substr(3);
    }
    if (number.empty() || number.find_first_not_of("0123456789") != std::string::npos || (role != "laser" && role != "ignore")) {
      throw Error(fmt::format("--outputs: expected P<n>=laser|ignore or fan<n>=laser|ignore, got '{}'", word));
    }
    const double n = number_of("--outputs", number, text);
    check("--outputs", n, 0.0, motion::max_code_number, "");
    output.number = static_cast<int>(n);
    output.role = role == "laser" ? motion::OutputRole::laser : motion::OutputRole::ignored;
    outputs.push_back(output);
  }
  return outputs;
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
  cmd->add_option("--work-offset-mm", a.work_offset_mm, "G54 origin in the robot frame: X,Y (mm, one word)");
  cmd->add_option("--start-mm", a.start_mm, "Where the robot starts: X,Y (mm, one word); default: the first move's target");
  cmd->add_option("--blend", a.blend,
                  "A program that names neither G61 nor G64: on (round corners within --blend-tolerance-mm, as "
                  "GRBL, Marlin and LinuxCNC do) or off (exact stop at every corner)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--blend-tolerance-mm", a.blend_tolerance_mm,
                  "Corner tolerance of a G64 without P and of a program that names no mode (mm)")
      ->capture_default_str();
  cmd->add_option("--chords", a.chords,
                  "G64 chains of short lines: blend (a fillet at each vertex), fit (one smooth curve within P) or "
                  "auto (fit the chains merged from staircases, blend the rest)")
      ->check(CLI::IsMember({"blend", "fit", "auto"}))
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
  cmd->add_option("--ignore-m", a.ignore_m,
                  "Vendor M-codes accepted and ignored with a warning (comma list, or none); other unknown M-codes "
                  "are refused")
      ->capture_default_str();
  cmd->add_option("--outputs", a.outputs,
                  "What outputs drive: P<n>=laser|ignore (M62/M63 P<n>), fan<n>=laser|ignore (M106/M107 P<n>), comma "
                  "list; default: every output is the laser");
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
  o.gcode.initial_mode = a.blend == "off" ? motion::JunctionMode::exact_stop : motion::JunctionMode::blend;
  check("--junction-time-ms", a.junction_time_ms, 0.0, 1000.0, "ms");
  o.planner.junction.junction_time_s = a.junction_time_ms * 1e-3;
  o.planner.junction.fit_chords = a.chords == "fit";
  o.planner.junction.fit_merged_chords = a.chords != "blend";
  o.planner.max_lookahead_segments = a.lookahead;
  o.gcode.strict = a.strict;
  o.gcode.dwell_p_units = a.dwell_p_units == "ms" ? motion::DwellUnits::milliseconds : motion::DwellUnits::seconds;
  check("--s-max", a.s_max, 1e-6, 1e9, "");
  o.gcode.s_max = a.s_max;
  o.gcode.program_stop_dwell_s = stop_dwell_s(a.program_stop);
  o.gcode.skip_block_delete = a.block_delete == "skip";
  o.gcode.ignored_m_codes = m_codes(a.ignore_m);
  o.gcode.outputs = outputs_of(a.outputs);
  o.gcode.on_warnings = print_gcode_warnings;
  try {
    motion::validate(o.gcode);
  } catch (const Error& e) {  // the codes the reader runs itself
    throw Error(std::string("--ignore-m: ") + e.what());
  }
  return o;
}

void print_gcode_warnings(const std::string& file, const std::vector<motion::GcodeWarning>& warnings) {
  for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", motion::describe(w, file).c_str());
}

}  // namespace stiffpath::cli

namespace stiffpath::cli {

namespace {
// "12-480" or "12".
std::string lines_of(const motion::SlowStretch& s) {
  return s.first_line == s.last_line ? std::to_string(s.first_line) : fmt::format("{}-{}", s.first_line, s.last_line);
}

// The limits of a stretch, most time first, as "curvature steps (...) 78 %, ...".
std::string limits_of(const motion::SlowStretch& s) {
  std::vector<std::pair<double, motion::SpeedLimit>> parts;
  for (std::size_t k = 0; k < s.lost_s.size(); ++k) {
    if (s.lost_s[k] > 0.005 * s.lost_total_s()) parts.emplace_back(s.lost_s[k], static_cast<motion::SpeedLimit>(k));
  }
  std::sort(parts.begin(), parts.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::string text;
  const double total = s.lost_total_s();
  for (std::size_t k = 0; k < parts.size() && k < 3; ++k) {
    text += fmt::format("{}{} {:.0f} %", k == 0 ? "" : ", ", motion::to_string(parts[k].second), 100.0 * parts[k].first / total);
  }
  return text;
}
}  // namespace

void print_slowdowns(std::FILE* out, const motion::SlowdownReport& r) {
  const double lost = r.planned_s() - r.programmed_s();
  fmt::print(out, "time: {:.4f} s planned, {:.4f} s at the programmed feeds ({:.3f}x){}\n", r.planned_s(), r.programmed_s(),
             r.programmed_s() > 0.0 ? r.planned_s() / r.programmed_s() : 1.0,
             r.feed_above_limit_s() > 0.0
                 ? fmt::format("; feeds above the speed limit would take {:.4f} s less", r.feed_above_limit_s())
                 : std::string());
  if (!(lost > 1e-6)) return;
  fmt::print(out, "lost to:\n");
  std::vector<std::pair<double, motion::SpeedLimit>> totals;
  for (std::size_t k = 0; k < r.lost_s().size(); ++k) {
    if (r.lost_s()[k] > 5e-5) totals.emplace_back(r.lost_s()[k], static_cast<motion::SpeedLimit>(k));
  }
  std::sort(totals.begin(), totals.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (const auto& [seconds, limit] : totals) {
    fmt::print(out, "  {:>9.4f} s  {:<15} {}\n", seconds, motion::to_string(limit), motion::describe(limit));
  }
  const auto stretches = r.slowest();
  if (stretches.empty()) return;
  fmt::print(out, "slowest stretches:\n  {:<13} {:>9} {:>9} {:>9} {:>8}  {}\n", "G-code lines", "from s", "lost s", "at feed",
             "low mm/s", "limits");
  for (const auto& s : stretches) {
    fmt::print(out, "  {:<13} {:>9.4f} {:>9.4f} {:>8.0f}% {:>8.1f}  {}\n", lines_of(s), s.start_s, s.lost_total_s(),
               s.duration_s > 0.0 ? 100.0 * s.programmed_s / s.duration_s : 100.0, units::m_to_mm(s.lowest_speed_m_s),
               limits_of(s));
  }
}

nlohmann::json slowdowns_json(const motion::SlowdownReport& r) {
  const auto by_limit = [](const auto& seconds) {
    nlohmann::json out = nlohmann::json::object();
    for (std::size_t k = 0; k < seconds.size(); ++k) {
      if (seconds[k] > 0.0) out[motion::to_string(static_cast<motion::SpeedLimit>(k))] = tidy(seconds[k]);
    }
    return out;
  };
  nlohmann::json stretches = nlohmann::json::array();
  for (const auto& s : r.slowest()) {
    stretches.push_back({{"first_line", s.first_line},
                         {"last_line", s.last_line},
                         {"start_s", tidy(s.start_s)},
                         {"duration_s", tidy(s.duration_s)},
                         {"programmed_s", tidy(s.programmed_s)},
                         {"lost_s", tidy(s.lost_total_s())},
                         {"lowest_speed_m_s", tidy(s.lowest_speed_m_s)},
                         {"limits", by_limit(s.lost_s)}});
  }
  return {{"planned_time_s", tidy(r.planned_s())},
          {"programmed_time_s", tidy(r.programmed_s())},
          {"feed_above_limit_s", tidy(r.feed_above_limit_s())},
          {"shortcut_s", tidy(r.shortcut_s())},
          {"lost_s", by_limit(r.lost_s())},
          {"stretches", stretches}};
}

}  // namespace stiffpath::cli
