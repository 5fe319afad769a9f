// `stiffpath simulate`: a joint trajectory from `stiffpath run` through the digital twin, measured like the thesis's marks.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <memory>

#include "commands.hpp"
#include "progress.hpp"
#include "robot_flags.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/joint_reader.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/simulation/run_metrics.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::cli {

namespace {
struct SimulateArgs {
  std::string joints;
  std::string robot;  // default: the binary file's robot (a preset), else oc-gu
  int sides = 1;
  double perturbation = simulation::TrueComplianceOptions{}.perturbation;
  std::uint64_t seed = simulation::TrueComplianceOptions{}.seed;
  simulation::SimulationOptions sim;
  std::string marks_csv;
  bool json = false, quiet = false;
};

// Records in a joint file, for the progress bar: from the size for the binary format, lines for CSV.
double record_count(const std::string& path, bool binary) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec) return 1.0;
  if (binary) return std::max(1.0, (static_cast<double>(bytes) - job::kBinaryHeaderBytes) / job::kBinaryRecordBytes);
  std::ifstream in(path, std::ios::binary);
  double lines = 0;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) lines += static_cast<double>(std::count(buffer, buffer + in.gcount(), '\n'));
  return std::max(1.0, lines - 1);
}

// The laser's mark as x_mm, y_mm in marking order, y flipped to the scan's downward axis, so that
// `stiffpath render-scan --path-csv` draws it as the paper would show it.
void write_marks(const std::string& path, const simulation::SimulationResult& run) {
  core::AtomicFile file(path);
  auto& out = file.stream();
  out << "x_mm,y_mm\n";
  for (const auto& p : run.marked) out << fmt::format("{:.6f},{:.6f}\n", p.x() * 1e3, -p.y() * 1e3);
  file.commit();
}

void simulate(const SimulateArgs& a) {
  job::JointReader reader(a.joints);
  const std::string written_for = reader.mechanism();
  kinematics::Robot robot;
  if (!a.robot.empty()) {
    robot = kinematics::load_robot(a.robot);
    if (!written_for.empty() && written_for != robot.name) {
      throw Error(SourceLocation{a.joints}, fmt::format("the joint file was written for robot '{}', not for '{}' "
                                                        "(named by --robot {})",
                                                        written_for, robot.name, a.robot));
    }
  } else if (!written_for.empty()) {
    const auto presets = kinematics::preset_names();
    if (std::find(presets.begin(), presets.end(), written_for) == presets.end()) {
      throw Error(SourceLocation{a.joints},
                  fmt::format("the joint file was written for robot '{}', which is not a preset: name its robot file "
                              "with --robot",
                              written_for));
    }
    robot = kinematics::load_robot(written_for);
  } else {
    robot = load_robot_flag("");
  }
  const auto truth = simulation::make_true_compliance(robot, {"", a.perturbation, a.seed});
  Progress progress("simulate", a.quiet);
  const double total = progress.enabled() ? record_count(a.joints, reader.binary()) : 1.0;
  double done = 0;
  const simulation::SimulationResult run = simulation::simulate(
      [&] {
        if (++done == 1 || static_cast<long>(done) % 2048 == 0) progress.update(done / total);
        return reader.next();
      },
      robot, truth, a.sim);
  progress.finish();
  const simulation::RunMetrics m = simulation::measure_run(run, a.sides);
  if (!a.marks_csv.empty()) write_marks(a.marks_csv, run);
  const auto corner_metric = [&m](double value_m) -> nlohmann::json {
    return m.corners == 0 ? nlohmann::json(nullptr) : nlohmann::json(tidy(value_m * 1e3));
  };
  if (a.json) {
    print_json({{"joints", a.joints},
                {"robot", robot.name},
                {"duration_s", tidy(run.duration_s)},
                {"marked_points", run.marked.size()},
                {"length_mm", tidy(m.length_m * 1e3)},
                {"commanded_length_mm", tidy(m.commanded_length_m * 1e3)},
                {"length_error_mm", tidy(m.length_error_m * 1e3)},
                {"deviation_area_mm2", tidy(m.deviation_area_m2 * 1e6)},
                {"max_deviation_mm", tidy(m.max_deviation_m * 1e3)},
                {"path_accuracy_mm", tidy(m.path_accuracy_m * 1e3)},
                {"corners", m.corners},
                {"cornering_round_off_mm", corner_metric(m.cornering_round_off_m)},
                {"cornering_overshoot_mm", corner_metric(m.cornering_overshoot_m)},
                {"residual_vibration_mm", tidy(m.residual_vibration_m * 1e3)},
                {"peak_deflection_mm", tidy(m.peak_deflection_m * 1e3)}});
    return;
  }
  fmt::print("{}: simulated {:.4f} s on {} (C_true perturbation {:g}, seed {})\n", a.joints, run.duration_s, robot.name,
             a.perturbation, a.seed);
  fmt::print("  length {:.4f} mm (commanded {:.4f} mm, error {:+.4f} mm)\n", m.length_m * 1e3,
             m.commanded_length_m * 1e3, m.length_error_m * 1e3);
  fmt::print("  deviation area {:.4f} mm^2, max deviation {:.4f} mm, path accuracy AT_p {:.4f} mm\n",
             m.deviation_area_m2 * 1e6, m.max_deviation_m * 1e3, m.path_accuracy_m * 1e3);
  if (m.corners > 0) {
    fmt::print("  {} corners: round-off CR {:.4f} mm, overshoot CO {:.4f} mm (largest)\n", m.corners,
               m.cornering_round_off_m * 1e3, m.cornering_overshoot_m * 1e3);
  }
  fmt::print("  peak tip deflection {:.4f} mm, residual vibration {:.4f} mm\n", m.peak_deflection_m * 1e3,
             m.residual_vibration_m * 1e3);
}
}  // namespace

void add_simulate_command(CLI::App& app) {
  auto a = std::make_shared<SimulateArgs>();
  auto* cmd = app.add_subcommand("simulate", "Run a joint trajectory (from `run`) on the digital twin and measure the mark");
  cmd->add_option("joints", a->joints, "Joint trajectory file (CSV or binary)")->required();
  add_robot_flag(cmd, a->robot)->description("Robot (preset or file) the joints were made for (default: the binary "
                                            "file's preset, else oc-gu); its data give C_true");
  cmd->add_option("--sides", a->sides, "Straight sides of the path: 1 (line) or 3 (triangle)")
      ->check(CLI::Range(1, 12))->capture_default_str();
  cmd->add_option("--perturbation", a->perturbation, "Relative perturbation of C_true")
      ->check(CLI::Range(0.0, 0.5))->capture_default_str();
  cmd->add_option("--seed", a->seed, "Seed of the perturbation")->capture_default_str();
  cmd->add_option("--damping-ratio", a->sim.plant.tip_damping_ratio, "Damping ratio of the tip's modes")
      ->check(CLI::Range(0.0, 2.0))->capture_default_str();
  cmd->add_option("--servo-bandwidth-hz", a->sim.plant.servo_bandwidth_hz, "Joint position-loop bandwidth")
      ->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--step-rate-hz", a->sim.plant.step_rate_hz, "Integration rate")
      ->check(CLI::Range(1000.0, 1e7))->capture_default_str();
  cmd->add_option("--marks-csv", a->marks_csv, "Also write the mark (x_mm, y_mm, y down) for `render-scan --path-csv`");
  cmd->add_flag("--json", a->json, "Print the metrics as JSON");
  cmd->add_flag("--quiet", a->quiet, "No progress bar (it is shown only on a terminal anyway)");
  cmd->callback([a] { simulate(*a); });
}

}  // namespace stiffpath::cli
