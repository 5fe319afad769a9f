// `stiffpath plan`: G-code to a jerk-limited trajectory sampled at 2 kHz (thesis §4.3, fig. 4.3), as CSV.
#include <fmt/format.h>
#include <memory>
#include <optional>
#include <vector>

#include "commands.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/motion/trajectory_csv.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::cli {

namespace {

struct PlanArgs {
  std::string job;
  std::string accel = "5g";
  std::optional<double> jerk_m_s3;
  double max_velocity_mm_s = units::m_to_mm(motion::default_max_velocity_m_s);
  double rate_hz = motion::default_sample_rate_hz;
  std::vector<double> work_offset_mm;
  std::vector<double> start_mm;
  double blend_tolerance_mm = 0.01;
  double junction_time_ms = 0.5;
  std::size_t lookahead = 0;
  std::string output;
  bool json = false;
};

motion::PlanOptions plan_options(const PlanArgs& a) {
  motion::PlanOptions o;
  o.limits.max_acceleration_m_s2 = units::parse_acceleration_m_s2(a.accel);
  o.limits.max_jerk_m_s3 = a.jerk_m_s3.value_or(motion::default_jerk_m_s3(o.limits.max_acceleration_m_s2));
  o.limits.max_velocity_m_s = units::mm_to_m(a.max_velocity_mm_s);
  o.rate_hz = a.rate_hz;
  if (!a.work_offset_mm.empty()) {
    o.gcode.work_offset_m = {units::mm_to_m(a.work_offset_mm[0]), units::mm_to_m(a.work_offset_mm[1])};
  }
  if (!a.start_mm.empty()) o.gcode.start_position_m = motion::Vec2(units::mm_to_m(a.start_mm[0]), units::mm_to_m(a.start_mm[1]));
  o.gcode.default_blend_tolerance_m = units::mm_to_m(a.blend_tolerance_mm);
  o.planner.junction.junction_time_s = a.junction_time_ms * 1e-3;
  o.planner.max_lookahead_segments = a.lookahead;
  return o;
}

void run_plan(const PlanArgs& a) {
  const motion::PlanOptions options = plan_options(a);
  motion::TrajectoryStream stream(a.job, options);
  const motion::TrajectorySummary summary = a.output.empty()
                                                ? motion::summarize(stream, options.rate_hz)
                                                : motion::write_trajectory_csv(stream, options.rate_hz, a.output);
  const auto& planner = stream.planner_statistics();
  if (a.json) {
    print_json({{"job", a.job},
                {"duration_s", tidy(summary.duration_s)},
                {"samples", summary.samples},
                {"segments", stream.segments()},
                {"rate_hz", tidy(options.rate_hz)},
                {"peak_velocity_m_s", tidy(summary.peak_velocity_m_s)},
                {"peak_acceleration_m_s2", tidy(summary.peak_acceleration_m_s2)},
                {"peak_jerk_m_s3", tidy(summary.peak_jerk_m_s3)},
                {"laser_on_s", tidy(summary.laser_on_s)},
                {"max_velocity_m_s", tidy(options.limits.max_velocity_m_s)},
                {"max_acceleration_m_s2", tidy(options.limits.max_acceleration_m_s2)},
                {"max_jerk_m_s3", tidy(options.limits.max_jerk_m_s3)},
                {"lookahead_peak_segments", planner.peak_window},
                {"output", a.output.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.output)}});
    return;
  }
  fmt::print("{}: {} segment{}, {} samples at {:g} Hz, duration {:.6f} s\n", a.job, stream.segments(),
             stream.segments() == 1 ? "" : "s", summary.samples, options.rate_hz, summary.duration_s);
  fmt::print("limits: v {:.1f} mm/s, a {:.3f} m/s^2 ({:.2f} g), j {:.1f} m/s^3\n", units::m_to_mm(options.limits.max_velocity_m_s),
             options.limits.max_acceleration_m_s2, options.limits.max_acceleration_m_s2 / units::standard_gravity_m_s2,
             options.limits.max_jerk_m_s3);
  fmt::print("peaks:  v {:.1f} mm/s, a {:.3f} m/s^2 ({:.2f} g), j {:.1f} m/s^3\n", units::m_to_mm(summary.peak_velocity_m_s),
             summary.peak_acceleration_m_s2, summary.peak_acceleration_m_s2 / units::standard_gravity_m_s2,
             summary.peak_jerk_m_s3);
  fmt::print("laser on {:.4f} s; the look-ahead held at most {} segment{}\n", summary.laser_on_s, planner.peak_window,
             planner.peak_window == 1 ? "" : "s");
  if (!a.output.empty()) fmt::print("wrote {}\n", a.output);
}

}  // namespace

void add_plan_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("plan", "G-code -> jerk-limited trajectory sampled at a fixed rate (thesis 4.3)");
  auto a = std::make_shared<PlanArgs>();
  cmd->add_option("job", a->job, "G-code program (mm, robot frame unless --work-offset-mm)")->required();
  cmd->add_option("--accel", a->accel, "Acceleration limit, e.g. 5g or 49 (m/s^2)")->capture_default_str();
  cmd->add_option("--jerk", a->jerk_m_s3, "Jerk limit (m/s^3); default: accel / 5 ms")->check(CLI::PositiveNumber);
  cmd->add_option("--max-velocity-mm-s", a->max_velocity_mm_s, "Speed limit, also of G0 (mm/s)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--rate", a->rate_hz, "Sampling rate (Hz)")->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--work-offset-mm", a->work_offset_mm, "G54 origin in the robot frame: X,Y (mm)")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--start-mm", a->start_mm, "Where the robot starts: X,Y (mm); default: the first move's target")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--blend-tolerance-mm", a->blend_tolerance_mm, "Corner tolerance of a G64 without P (mm)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--junction-time-ms", a->junction_time_ms, "Junction time: steps of v and a allowed at joins (ms)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--lookahead", a->lookahead, "Look-ahead bound in segments (0: whole program)")->capture_default_str();
  cmd->add_option("-o,--output", a->output, "Write the samples to this CSV file");
  cmd->add_flag("--json", a->json, "Print the summary as JSON");
  cmd->callback([a] { run_plan(*a); });
}

}  // namespace stiffpath::cli
