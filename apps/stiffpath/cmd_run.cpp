// `stiffpath run`: the main job — G-code to compensated joint commands at 2 kHz (thesis fig. 4.3).
#include <cstdio>
#include <fmt/format.h>
#include <fstream>
#include <memory>

#include "commands.hpp"
#include "progress.hpp"
#include "motion_flags.hpp"
#include "robot_flags.hpp"
#include "stiffpath/job/job.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::cli {

namespace {
struct RunArgs {
  std::string job;
  std::string robot;
  compliance::ModelRequest request;  // default: the robot's own model
  bool no_compensation = false;
  double gain = 1.0;
  std::string accel_source = "analytic";
  std::string outside;
  std::string output;
  std::string format = "csv";
  bool json = false, quiet = false;
  MotionFlags motion;
};

int count_lines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  int lines = 0;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) lines += buffer[i] == '\n';
  }
  return lines;
}

// The job's progress as the share of its G-code lines done, on the shared progress bar.
job::Progress progress_bar(const std::string& job, Progress& bar) {
  if (!bar.enabled()) return {};
  const int total = std::max(count_lines(job), 1);
  return [total, &bar](std::uint64_t samples, int line) {
    bar.update(static_cast<double>(line) / total, fmt::format("line {}/{}  {:.1f} M samples", line, total,
                                                              static_cast<double>(samples) / 1e6));
  };
}

void run(const RunArgs& a) {
  const auto robot = load_robot_flag(a.robot);
  const bool compensating = !a.no_compensation && a.gain != 0.0;
  // A robot with no compliance data yet can still run without compensation (reach and limits only).
  const bool has_data = !robot.compliance.table.empty() || !robot.compliance.model.empty() || !a.request.model.empty();
  std::shared_ptr<const compliance::Model> model;
  std::string model_name = "none";
  if (compensating || has_data) {
    auto loaded = compliance::load_robot_model(robot, a.request);
    if (!a.outside.empty()) loaded.model->set_outside_policy(compliance::parse_outside_policy(a.outside));
    model_name = loaded.label;
    model.reset(loaded.model.release());
  }
  const compensation::Compensator compensator(robot, model, {a.gain, !a.no_compensation, true});
  const motion::PlanOptions options = plan_options(a.motion, robot);
  const auto acceleration = job::parse_acceleration_source(a.accel_source);

  motion::TrajectoryStream stream(a.job, options);
  std::unique_ptr<job::JointWriter> writer;
  if (!a.output.empty()) {
    writer = job::make_joint_writer(job::parse_output_format(a.format), a.output, options.rate_hz, robot.name);
  }
  Progress bar("run", a.quiet);
  const auto progress = progress_bar(a.job, bar);
  const job::JobSummary s = job::run_job(stream, compensator, writer.get(), a.job, options.rate_hz, acceleration, progress);
  bar.finish();

  if (a.json) {
    print_json({{"job", a.job},
                {"robot", robot.name},
                {"model", model_name},
                {"compensation", compensating},
                {"gain", a.no_compensation ? 0.0 : a.gain},
                {"acceleration_source", a.accel_source},
                {"duration_s", tidy(s.duration_s)},
                {"samples", s.samples},
                {"rate_hz", tidy(options.rate_hz)},
                {"peak_deflection_um", tidy(units::m_to_um(s.peak_deflection_m))},
                {"peak_correction_um", tidy(units::m_to_um(s.peak_correction_m))},
                {"peak_force_n", tidy(s.peak_force_N)},
                {"peak_joint_velocity_rad_s", tidy(s.peak_joint_velocity_rad_s)},
                {"peak_joint_acceleration_rad_s2", tidy(s.peak_joint_acceleration_rad_s2)},
                {"samples_outside_grid", s.samples_outside_grid},
                {"output", a.output.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.output)}});
    return;
  }
  fmt::print("{}: {} on {} with {}{}\n", a.job, compensating ? "compensated" : "not compensated", robot.name,
             model_name, compensating && a.gain != 1.0 ? fmt::format(" (gain {:g})", a.gain) : "");
  fmt::print("  {} samples at {:g} Hz, duration {:.4f} s\n", s.samples, options.rate_hz, s.duration_s);
  fmt::print("  peak D'Alembert force {:.1f} N, predicted deflection {:.1f} um, correction {:.1f} um\n", s.peak_force_N,
             units::m_to_um(s.peak_deflection_m), units::m_to_um(s.peak_correction_m));
  fmt::print("  peak joint velocity {:.2f} rad/s, acceleration {:.1f} rad/s^2\n", s.peak_joint_velocity_rad_s,
             s.peak_joint_acceleration_rad_s2);
  if (s.samples_outside_grid > 0) {
    fmt::print("  {} samples outside the compliance model's measured region ({})\n", s.samples_outside_grid,
               model ? compliance::to_string(model->outside_policy()) : "no model");
  }
  if (!a.output.empty()) fmt::print("  wrote {}\n", a.output);
}
}  // namespace

void add_run_command(CLI::App& app) {
  auto a = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "The main job: G-code -> compliance-compensated joint commands (fig. 4.3)");
  cmd->add_option("job", a->job, "G-code program")->required();
  add_robot_flag(cmd, a->robot);
  add_model_flags(cmd, a->request);
  cmd->add_flag("--no-compensation", a->no_compensation, "Plan and convert to joints without correcting");
  cmd->add_option("--gain", a->gain, "Compensation gain k in p_cmd = p - k*delta")->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--accel-source", a->accel_source, "analytic (profile) or numeric (thesis: 2nd difference)")
      ->capture_default_str();
  cmd->add_option("--outside", a->outside,
                  "A sample more than 1 mm outside the model's measured region: error (refuse), clamp or extrapolate "
                  "(default: the model's, error unless it was fitted otherwise)");
  cmd->add_option("-o,--output", a->output, "Joint trajectory file (written atomically)");
  cmd->add_option("--format", a->format, "csv or bin")->capture_default_str();
  cmd->add_flag("--json", a->json, "Print the summary as JSON");
  cmd->add_flag("--quiet", a->quiet, "No progress bar (it is shown only on a terminal anyway)");
  add_motion_flags(cmd, a->motion);
  cmd->callback([a] { run(*a); });
}

}  // namespace stiffpath::cli
