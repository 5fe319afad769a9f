// `stiffpath run`: the main job — G-code to compensated joint commands at 2 kHz (thesis fig. 4.3).
#include <cstdio>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "job_budget.hpp"
#include "progress.hpp"
#include "motion_flags.hpp"
#include "robot_flags.hpp"
#include "stiffpath/compensation/run_filters.hpp"
#include "stiffpath/compensation/tip_modes.hpp"
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
  std::string method = "dynamic";
  std::optional<double> damping_ratio;  // unset: the robot file's tip_damping_ratio
  double smooth_ms = compensation::kDefaultSmoothing_s * 1e3;
  std::string shaper = "none";
  std::string outside;
  std::string output;
  std::string format = "csv";
  bool json = false, quiet = false;
  std::uint64_t max_samples = default_max_samples;
  MotionFlags motion;
};

//! Bytes of one joint CSV row (measured rows of the thesis's jobs are 125-135 bytes; rounded up) and
//! of a binary record (docs/compensation.md), for the output budget checked before writing.
constexpr OutputEstimate joint_csv_estimate{140.0, 200.0, "joint CSV"};
constexpr OutputEstimate joint_bin_estimate{112.0, 64.0, "binary joint records"};

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

// The rectangle the planned job covers (one planning pass without compensation).
compliance::GridBounds job_region(const std::string& job, const motion::PlanOptions& options) {
  motion::TrajectoryStream stream(job, options);
  auto box = compliance::GridBounds::none();
  while (const auto s = stream.next()) box.include(s->position_m);
  if (box.x_min > box.x_max) throw Error(SourceLocation{job}, "the program has no motion");
  return box;
}

void run(const RunArgs& a) {
  const auto robot = load_robot_flag(a.robot);
  core::check_distinct_files(robot_inputs(robot, true, {{"gcode", a.job}, {"--model", a.request.model}}), {{"-o", a.output}});
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
  const double damping_ratio = a.damping_ratio.value_or(robot.tip_damping_ratio);
  const compensation::CompensatorOptions comp_options{.gain = a.gain,
                                                      .enabled = !a.no_compensation,
                                                      .check_limits = true,
                                                      .method = compensation::parse_method(a.method),
                                                      .damping_ratio = damping_ratio};
  const compensation::Compensator compensator(robot, model, comp_options);
  const auto shaper = compensation::parse_filter_kind(a.shaper);
  if (shaper == compensation::FilterKind::smooth) throw Error("--shaper: expected none, zv or zvd, got 'smooth' (see --smooth-ms)");
  if (!(a.smooth_ms >= 0.0 && a.smooth_ms <= 1000.0)) throw Error(fmt::format("--smooth-ms: must lie in 0..1000, got {}", a.smooth_ms));

  // --jerk auto and the shapers need the tip's lowest natural frequency on the job's region.
  MotionFlags motion_flags = a.motion;
  double lowest_hz = 0.0;
  if (motion_flags.jerk == "auto" || shaper != compensation::FilterKind::none) {
    if (!model) throw Error("--jerk auto and --shaper need the robot's compliance model");
    MotionFlags first_pass = motion_flags;
    if (first_pass.jerk == "auto") first_pass.jerk.clear();
    lowest_hz = compensation::lowest_natural_frequency_hz(*model, robot.moving_mass_kg,
                                                          job_region(a.job, plan_options(first_pass, robot)));
    if (!(lowest_hz > 0.0)) throw Error("the compliance model gives the tip no natural frequency on this job");
    if (motion_flags.jerk == "auto") {
      motion_flags.jerk_m_s3 = units::parse_acceleration_m_s2(motion_flags.accel) * lowest_hz;
    }
  }
  const motion::PlanOptions options = plan_options(motion_flags, robot);
  compensation::RunFilterOptions filter_options;
  filter_options.smooth_s = a.smooth_ms * 1e-3;
  filter_options.shaper = shaper;
  filter_options.damping_ratio = damping_ratio;
  filter_options.min_frequency_hz = lowest_hz;
  compensation::FilterChain filters = compensation::make_run_filters(options.rate_hz, filter_options, model, robot.moving_mass_kg);
  const auto acceleration = job::parse_acceleration_source(a.accel_source);

  const auto format = job::parse_output_format(a.format);
  (void)check_job_budget(a.job, options, a.max_samples, a.output,
                         format == job::OutputFormat::csv ? joint_csv_estimate : joint_bin_estimate, "job",
                         static_cast<std::uint64_t>(filters.delay_samples()), static_cast<std::uint64_t>(filters.rest_samples()));
  motion::TrajectoryStream stream(a.job, options);
  std::unique_ptr<job::JointWriter> writer;
  if (!a.output.empty()) {
    writer = job::make_joint_writer(format, a.output, options.rate_hz, {robot.name, robot.geometry_hash()});
  }
  Progress bar("run", a.quiet);
  const auto progress = progress_bar(a.job, bar);
  const job::JobSummary s = job::run_job(stream, compensator, writer.get(), a.job, options.rate_hz, acceleration, progress,
                                            &filters);
  bar.finish();

  // With -o - the joint records own standard output, so the summary goes to standard error.
  std::FILE* info = a.output == "-" ? stderr : stdout;
  if (a.json) {
    const nlohmann::json summary_json{{"job", a.job},
                {"robot", robot.name},
                {"model", model_name},
                {"compensation", compensating},
                {"gain", a.no_compensation ? 0.0 : a.gain},
                {"acceleration_source", a.accel_source},
                {"method", compensating ? a.method : "none"},
                {"damping_ratio", tidy(damping_ratio)},
                {"smooth_ms", tidy(a.smooth_ms)},
                {"shaper", a.shaper},
                {"jerk_m_s3", tidy(options.limits.max_jerk_m_s3)},
                {"lowest_frequency_hz", lowest_hz > 0.0 ? nlohmann::json(tidy(lowest_hz)) : nlohmann::json(nullptr)},
                {"duration_s", tidy(s.duration_s)},
                {"samples", s.samples},
                {"rate_hz", tidy(options.rate_hz)},
                {"peak_deflection_um", tidy(units::m_to_um(s.peak_deflection_m))},
                {"peak_correction_um", tidy(units::m_to_um(s.peak_correction_m))},
                {"peak_force_n", tidy(s.peak_force_N)},
                {"peak_joint_velocity_rad_s", tidy(s.peak_joint_velocity_rad_s)},
                {"peak_joint_acceleration_rad_s2", tidy(s.peak_joint_acceleration_rad_s2)},
                {"samples_outside_grid", s.samples_outside_grid},
                {"slowdowns", slowdowns_json(stream.slowdowns())},
                {"output", a.output.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.output)}};
    if (a.output == "-") {
      std::cerr << summary_json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    } else {
      print_json(summary_json);
    }
    return;
  }
  fmt::print(info, "{}: {} on {} with {}{}\n", a.job, compensating ? "compensated" : "not compensated", robot.name,
             model_name, compensating && a.gain != 1.0 ? fmt::format(" (gain {:g})", a.gain) : "");
  if (compensating) {
    fmt::print(info, "  {} compensation (damping ratio {:g}), reference smoothed over {:g} ms, shaper {}, jerk {:.0f} m/s^3\n",
               a.method, damping_ratio, a.smooth_ms, a.shaper, options.limits.max_jerk_m_s3);
  }
  fmt::print(info, "  {} samples at {:g} Hz, duration {:.4f} s\n", s.samples, options.rate_hz, s.duration_s);
  fmt::print(info, "  peak D'Alembert force {:.1f} N, predicted deflection {:.1f} um, correction {:.1f} um\n", s.peak_force_N,
             units::m_to_um(s.peak_deflection_m), units::m_to_um(s.peak_correction_m));
  fmt::print(info, "  peak joint velocity {:.2f} rad/s, acceleration {:.1f} rad/s^2\n", s.peak_joint_velocity_rad_s,
             s.peak_joint_acceleration_rad_s2);
  if (s.samples_outside_grid > 0) {
    fmt::print(info, "  {} samples outside the compliance model's measured region ({})\n", s.samples_outside_grid,
               model ? compliance::to_string(model->outside_policy()) : "no model");
  }
  print_slowdowns(info, stream.slowdowns());
  if (!a.output.empty()) fmt::print(info, "  wrote {}\n", a.output);
}
}  // namespace

void add_run_command(CLI::App& app) {
  auto a = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "The main job: G-code -> compliance-compensated joint commands (fig. 4.3)");
  cmd->add_option("job", a->job, "G-code program")->required();
  add_robot_flag(cmd, a->robot);
  add_model_flags(cmd, a->request);
  cmd->add_flag("--no-compensation", a->no_compensation, "Plan and convert to joints without correcting");
  cmd->add_option("--gain", a->gain, "Compensation gain k in p_cmd = p - k*delta")->check(within(0.0, 10.0, ""))
      ->capture_default_str();
  cmd->add_option("--accel-source", a->accel_source, "analytic (profile) or numeric (thesis: 2nd difference)")
      ->capture_default_str();
  cmd->add_option("--compensation", a->method,
                  "dynamic (tip model with damping inverted) or quasi-static (the thesis's static deflection)")
      ->check(CLI::IsMember({"dynamic", "quasi-static"}))
      ->capture_default_str();
  cmd->add_option("--damping-ratio", a->damping_ratio,
                  "Damping ratio of the tip's modes assumed by dynamic compensation and the shapers (default: the "
                  "robot file's tip_damping_ratio, 0.05 when it gives none)")
      ->check(within(0.0, 0.9, ""));
  cmd->add_option("--smooth-ms", a->smooth_ms,
                  "Two moving averages of half this width over the planned reference (ms; 0: off): continuous "
                  "jerk and snap, so commands without velocity steps")
      ->capture_default_str();
  cmd->add_option("--shaper", a->shaper, "Input shaper following the tip's frequency: none, zv or zvd")
      ->check(CLI::IsMember({"none", "zv", "zvd"}))
      ->capture_default_str();
  cmd->add_option("--outside", a->outside,
                  "A sample more than 1 mm outside the model's measured region: error (refuse), clamp or extrapolate "
                  "(default: the model's, error unless it was fitted otherwise)");
  cmd->add_option("-o,--output", a->output, "Joint trajectory file (written atomically; - for standard output)")->check(output_name());
  add_max_samples_flag(cmd, a->max_samples);
  cmd->add_option("--format", a->format, "csv or bin")->capture_default_str();
  cmd->add_flag("--json", a->json, "Print the summary as JSON");
  cmd->add_flag("--quiet", a->quiet, "No progress bar (it is shown only on a terminal anyway)");
  add_motion_flags(cmd, a->motion);
  cmd->callback([a] { run(*a); });
}

}  // namespace stiffpath::cli
