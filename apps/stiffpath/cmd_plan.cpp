// `stiffpath plan`: G-code to a jerk-limited trajectory sampled at 2 kHz (thesis §4.3, fig. 4.3), as CSV.
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <fmt/format.h>
#include <memory>
#include <optional>
#include <vector>

#include "bounded.hpp"
#include "commands.hpp"
#include "job_budget.hpp"
#include "progress.hpp"
#include "motion_flags.hpp"
#include "robot_flags.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/motion/trajectory_csv.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::cli {

namespace {

//! Bytes of a typical CSV row (the x motion's rows average 110), for the size quoted in a refusal.
constexpr double csv_row_bytes = 120.0;

struct PlanArgs {
  std::string job;
  std::string output;
  std::string robot;
  bool json = false, quiet = false;
  std::uint64_t max_samples = default_max_samples;
  MotionFlags motion;
};

nlohmann::json warnings_json(const std::vector<motion::GcodeWarning>& warnings) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& w : warnings) {
    list.push_back({{"kind", motion::to_string(w.kind)}, {"message", w.message}, {"count", w.count}, {"first_line", w.first_line}});
  }
  return list;
}

// Passes the planned samples on and refuses the first one the robot cannot reach (singularity margins,
// assembly mode, joint position limits), naming its G-code line, time and point.
class WorkspaceCheck final : public motion::SampleSource {
 public:
  WorkspaceCheck(motion::SampleSource& inner, const kinematics::Robot& robot, std::string job, Progress& progress,
                 std::uint64_t total)
      : inner_(inner), robot_(robot), five_bar_(robot.five_bar()), job_(std::move(job)), progress_(progress),
        total_(std::max<std::uint64_t>(total, 1)) {}
  std::optional<motion::TrajectorySample> next() override {
    auto s = inner_.next();
    if (!s) return s;
    if (++count_ % 4096 == 0) progress_.update(static_cast<double>(count_) / static_cast<double>(total_));
    const auto r = five_bar_.solve_inverse(s->position_m);
    if (r.status != kinematics::Reach::ok || !robot_.within_limits(r.q)) {
      throw Error(SourceLocation{job_, s->line},
                  fmt::format("t = {:.4f} s: point (x = {:.4f} mm, y = {:.4f} mm) is outside robot {}'s workspace: {}",
                              s->t_s, units::m_to_mm(s->position_m.x()), units::m_to_mm(s->position_m.y()), robot_.name,
                              robot_.refusal(s->position_m)));
    }
    return s;
  }

 private:
  motion::SampleSource& inner_;
  const kinematics::Robot& robot_;
  kinematics::FiveBar five_bar_;
  std::string job_;
  Progress& progress_;
  std::uint64_t total_, count_ = 0;
};

void run_plan(const PlanArgs& a) {
  const auto robot = load_robot_flag(a.robot);
  core::check_distinct_files(robot_inputs(robot, false, {{"gcode", a.job}}), {{"-o", a.output}});
  motion::PlanOptions options = plan_options(a.motion, robot);
  if (a.json) options.gcode.on_warnings = nullptr;  // they go into the JSON document
  Progress progress("plan", a.quiet);
  progress.update(0.0, "sizing the plan");
  const std::uint64_t total =
      check_job_budget(a.job, options, a.max_samples, a.output, {csv_row_bytes, 0.0, "CSV"}, "plan").samples;
  motion::TrajectoryStream planned(a.job, options);
  WorkspaceCheck stream(planned, robot, a.job, progress, total);
  const motion::TrajectorySummary summary = a.output.empty()
                                                ? motion::summarize(stream, options.rate_hz)
                                                : motion::write_trajectory_csv(stream, options.rate_hz, a.output);
  progress.finish();
  const auto& planner = planned.planner_statistics();
  // With -o - the samples own standard output, so the summary goes to standard error.
  std::FILE* info = a.output == "-" ? stderr : stdout;
  if (a.json) {
    const nlohmann::json summary_json{{"job", a.job},
                {"robot", robot.name},
                {"duration_s", tidy(summary.duration_s)},
                {"samples", summary.samples},
                {"segments", planned.segments()},
                {"rate_hz", tidy(options.rate_hz)},
                {"peak_velocity_m_s", tidy(summary.peak_velocity_m_s)},
                {"peak_acceleration_m_s2", tidy(summary.peak_acceleration_m_s2)},
                {"peak_jerk_m_s3", tidy(summary.peak_jerk_m_s3)},
                {"laser_on_s", tidy(summary.laser_on_s)},
                {"laser_full_power_s", tidy(summary.laser_full_power_s)},
                {"peak_power", tidy(summary.peak_power)},
                {"max_velocity_m_s", tidy(options.limits.max_velocity_m_s)},
                {"max_acceleration_m_s2", tidy(options.limits.max_acceleration_m_s2)},
                {"max_jerk_m_s3", tidy(options.limits.max_jerk_m_s3)},
                {"lookahead_peak_segments", planner.peak_window},
                {"warnings", warnings_json(planned.warnings())},
                {"slowdowns", slowdowns_json(*planned.slowdowns())},
                {"output", a.output.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.output)}};
    if (a.output == "-") {
      std::cerr << summary_json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    } else {
      print_json(summary_json);
    }
    return;
  }
  fmt::print(info, "{}: {} segment{}, {} samples at {:g} Hz, duration {:.6f} s, inside robot {}'s workspace\n", a.job,
             planned.segments(), planned.segments() == 1 ? "" : "s", summary.samples, options.rate_hz, summary.duration_s,
             robot.name);
  fmt::print(info, "limits: v {:.1f} mm/s, a {:.3f} m/s^2 ({:.2f} g), j {:.1f} m/s^3\n", units::m_to_mm(options.limits.max_velocity_m_s),
             options.limits.max_acceleration_m_s2, options.limits.max_acceleration_m_s2 / units::standard_gravity_m_s2,
             options.limits.max_jerk_m_s3);
  fmt::print(info, "peaks:  v {:.1f} mm/s, a {:.3f} m/s^2 ({:.2f} g), j {:.1f} m/s^3\n", units::m_to_mm(summary.peak_velocity_m_s),
             summary.peak_acceleration_m_s2, summary.peak_acceleration_m_s2 / units::standard_gravity_m_s2,
             summary.peak_jerk_m_s3);
  fmt::print(info, "laser on {:.4f} s (peak power {:.1f} %, {:.4f} s at full power); the look-ahead held at most {} segment{}\n",
             summary.laser_on_s, 100.0 * summary.peak_power, summary.laser_full_power_s, planner.peak_window,
             planner.peak_window == 1 ? "" : "s");
  print_slowdowns(info, *planned.slowdowns());
  if (!a.output.empty()) fmt::print(info, "wrote {}\n", a.output);
}

}  // namespace

void add_plan_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("plan", "G-code -> jerk-limited trajectory sampled at a fixed rate (thesis 4.3)");
  auto a = std::make_shared<PlanArgs>();
  cmd->add_option("job", a->job, "G-code program (mm, robot frame unless --work-offset-mm)")->required();
  add_motion_flags(cmd, a->motion);
  add_robot_flag(cmd, a->robot)->description("Robot whose workspace every sample must lie in (default: oc-gu)");
  cmd->add_option("-o,--output", a->output, "Write the samples to this CSV file (- for standard output)")->check(output_name());
  add_max_samples_flag(cmd, a->max_samples);
  cmd->add_flag("--json", a->json, "Print the summary as JSON (errors too, on stderr)");
  cmd->add_flag("--quiet", a->quiet, "No progress bar (it is shown only on a terminal anyway)");
  cmd->callback([a] { run_plan(*a); });
}

}  // namespace stiffpath::cli
