// `stiffpath experiment`: the thesis's test matrix (§4.5) on the digital twin, or its robustness sweep, with tables and figures.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/core/atomic_directory.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/report/experiment_plots.hpp"
#include "stiffpath/report/gnuplot.hpp"
#include "stiffpath/report/robustness_plots.hpp"
#include "stiffpath/simulation/experiment.hpp"
#include "stiffpath/simulation/robustness.hpp"
#include "twin_flags.hpp"

namespace stiffpath::cli {

namespace {
struct ExperimentArgs {
  std::string output = "experiment";
  simulation::ExperimentOptions options;
  std::vector<std::string> paths;
  bool motions_given = false;
  bool robots_given = false;
  bool no_plots = false, quiet = false;
  std::string style = "screen";
  TwinFlags twin;
  bool robustness = false;
  simulation::RobustnessOptions robust;
  std::vector<std::string> variants{"thesis", "default"}, robust_variants{"without", "thesis", "default"};
  // Flags in the units people think in; the options are SI.
  std::vector<double> accelerations_g{1, 2, 3, 4, 5}, noise_um{0.0, 23.0};
  double robust_accel_g = 5.0;
};

// The files an experiment reads (robot files, G-code paths without their ":SIDES"), which its
// directory of outputs may never replace.
std::vector<core::NamedPath> experiment_inputs(const ExperimentArgs& a) {
  std::vector<core::NamedPath> inputs;
  for (const auto& robot : a.options.robots) inputs.push_back({"--robots", robot});
  for (const auto& path : a.paths) {
    const auto colon = path.rfind(':');
    const bool sides = colon != std::string::npos && colon + 1 < path.size() &&
                       path.find_first_not_of("0123456789", colon + 1) == std::string::npos;
    inputs.push_back({"--path", sides ? path.substr(0, colon) : path});
  }
  return inputs;
}

std::vector<simulation::CompensationVariant> variants(const std::vector<std::string>& names) {
  std::vector<simulation::CompensationVariant> out;
  for (const auto& name : names) out.push_back(core::parse_enum<simulation::CompensationVariant>(name));
  return out;
}

void robustness(ExperimentArgs& a, const std::filesystem::path& dir) {
  a.robust.base = a.options;
  if (a.robots_given) a.robust.robot = a.options.robots.front();
  const int runs = simulation::robustness_run_count(a.robust);
  fmt::print("robustness: {} runs on {} at {:g} g ({} seeds)\n", runs, a.robust.robot,
             a.robust.acceleration_m_s2 / units::standard_gravity_m_s2,
             a.robust.seeds);
  const auto start = std::chrono::steady_clock::now();
  core::check_output_directory(a.output);  // before the runs, not after them
  const auto rows = simulation::run_robustness(a.robust);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  core::AtomicDirectory out(dir, experiment_inputs(a));  // all or nothing: a full disk leaves no half
  core::write_file_atomically(out.staging() / "robustness.tsv", simulation::robustness_tsv(rows));
  const std::string table = simulation::robustness_markdown(rows);
  core::write_file_atomically(out.staging() / "robustness.md", table);
  std::string figures_line;
  if (!a.no_plots && !report::gnuplot_available()) {
    figures_line = "\ngnuplot not found: figures skipped\n";
  } else if (!a.no_plots) {
    std::filesystem::create_directory(out.staging() / "figures");
    const auto figures =
        report::write_robustness_figures(out.staging() / "figures", rows, report::parse_style(a.style));
    figures_line = fmt::format("\nfigures ({}, SVG, PNG, gnuplot script and data each): {}\n",
                               (dir / "figures").string(), fmt::join(figures, ", "));
  }
  out.commit();
  fmt::print("{} runs in {:.1f} s → {}\n\n{}{}", runs, seconds, (dir / "robustness.tsv").string(), table, figures_line);
}

void experiment(ExperimentArgs a) {
  a.options.variants = variants(a.variants);
  a.robust.variants = variants(a.robust_variants);
  a.options.accelerations_m_s2.clear();
  for (const double g : a.accelerations_g) a.options.accelerations_m_s2.push_back(g * units::standard_gravity_m_s2);
  a.robust.acceleration_m_s2 = a.robust_accel_g * units::standard_gravity_m_s2;
  a.robust.noise_sigmas_m.clear();
  for (const double um : a.noise_um) a.robust.noise_sigmas_m.push_back(units::um_to_m(um));
  apply_twin_flags(a.twin, a.options.simulation, a.options.truth);
  a.options.cg_lever = !a.twin.no_cg_lever;
  const std::filesystem::path dir(a.output);
  if (a.robustness) {
    robustness(a, dir);
    return;
  }
  for (const auto& path : a.paths) a.options.paths.push_back(simulation::user_motion(path));
  if (!a.paths.empty() && !a.motions_given) a.options.motions.clear();  // only the user's paths
  core::check_output_directory(a.output);  // before the runs, not after them (nothing is created yet)
  const auto start = std::chrono::steady_clock::now();
  const auto style = report::parse_style(a.style);
  Progress progress("experiment", a.quiet);
  const auto results = simulation::run_experiment(a.options, progress.callback());
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  core::AtomicDirectory out(dir, experiment_inputs(a));  // all or nothing: a full disk leaves no half
  core::write_file_atomically(out.staging() / "results.csv", simulation::experiment_csv(results));
  const std::string summary = simulation::experiment_summary(results);
  core::write_file_atomically(out.staging() / "summary.md", summary);
  std::string figures_line;
  if (!a.no_plots && !report::gnuplot_available()) {
    figures_line = "\ngnuplot not found: figures skipped\n";
  } else if (!a.no_plots) {
    std::filesystem::create_directory(out.staging() / "figures");
    // Without compensation and each variant run, as its own series, so that `plot results` on results.csv
    // draws the same figures.
    const auto figures =
        report::write_results_figures(out.staging() / "figures", report::results_from_runs(results), style);
    figures_line = fmt::format("\nfigures ({}, SVG, PNG, gnuplot script and data each): {}\n",
                               (dir / "figures").string(), fmt::join(figures, ", "));
  }
  out.commit();
  fmt::print("{} runs in {:.2f} s → {}\n\n{}{}", results.size(), seconds, (dir / "results.csv").string(), summary,
             figures_line);
}
}  // namespace

void add_experiment_command(CLI::App& app) {
  auto a = std::make_shared<ExperimentArgs>();
  auto* cmd = app.add_subcommand("experiment", "The thesis's test matrix on the digital twin of robots (figs. 4.9-4.11)");
  cmd->add_option("-o,--output", a->output, "Output directory (results.csv, summary.md, figures/)")->check(output_name())->capture_default_str();
  auto* robots = cmd->add_option("--robots,--robot,--mechanisms", a->options.robots, "Presets or robot files to run")
                     ->capture_default_str();
  auto* motions = cmd->add_option("--motions", a->options.motions,
                                  "x, y, triangle, y-mid-1 …, x-mid, triangle-off: placed in each robot's measured "
                                  "rectangle")->capture_default_str();
  cmd->add_option("--path", a->paths, "A G-code file of your own to run as FILE[:SIDES] (repeatable; without "
                                      "--motions only these run)");
  cmd->add_option("--accelerations-g", a->accelerations_g, "Acceleration limits (g)")
      ->check(within(0.1, 10.0, "g"))->capture_default_str();
  cmd->add_option("--variants", a->variants, "Compensations besides none: thesis (`run --thesis`: quasi-static, "
                                             "bilinear), default (what `run` does by default)")
      ->check(CLI::IsMember({"thesis", "default"}))->capture_default_str();
  cmd->add_option("--gain", a->options.compensator.gain, "Compensation gain")->check(within(0.0, 10.0, ""))
      ->capture_default_str();
  add_twin_flags(cmd, a->twin, a->options.simulation, a->options.truth);
  cmd->add_flag("--oracle-model", a->options.oracle_model,
                "Compensate with C_true (+ CG lever) itself: the error budget without model error");
  cmd->add_flag("--no-plots", a->no_plots, "Skip the gnuplot figures");
  cmd->add_flag("--robustness", a->robustness,
                "Sweep damping ratio, mass error, servo bandwidth and campaign noise over seeds instead "
                "(robustness.tsv, robustness.md, figures)");
  cmd->add_option("--seeds", a->robust.seeds, "Robustness: truth/campaign seeds 1 … N")
      ->check(CLI::Range(1, 100))->capture_default_str();
  cmd->add_option("--robust-motions", a->robust.motions, "Robustness: motions")->capture_default_str();
  cmd->add_option("--robust-accel-g", a->robust_accel_g, "Robustness: acceleration limit (g)")
      ->check(within(0.1, 10.0, "g"))->capture_default_str();
  cmd->add_option("--robust-variants", a->robust_variants, "Robustness: without, thesis, default")
      ->check(CLI::IsMember({"without", "thesis", "default"}))->capture_default_str();
  cmd->add_option("--damping-ratios", a->robust.damping_ratios, "Robustness: tip damping ratios")
      ->check(within(0.0, 2.0, ""))->capture_default_str();
  cmd->add_option("--mass-errors", a->robust.mass_errors, "Robustness: plant mass errors (fraction)")
      ->check(within(-0.5, 1.0, ""))->capture_default_str();
  cmd->add_option("--servo-bandwidths-hz", a->robust.servo_bandwidths_hz, "Robustness: servo bandwidths (Hz)")
      ->check(within(1.0, 2000.0, ""))->capture_default_str();
  cmd->add_option("--noise-um", a->noise_um, "Robustness: campaign noise sigma per coordinate (um)")
      ->check(within(0.0, 1000.0, ""))->capture_default_str();
  cmd->add_option("--max-runs", a->robust.max_runs, "Robustness: refuse sweeps with more runs")
      ->check(CLI::Range(1, 100000))->capture_default_str();
  cmd->add_option("--style", a->style, "Figures for the screen (colour) or paper (black and white, larger fonts)")
      ->check(CLI::IsMember({"screen", "paper"}))->capture_default_str();
  cmd->add_flag("--quiet", a->quiet, "No progress bar (it is shown only on a terminal anyway)");
  cmd->callback([a, motions, robots] {
    a->motions_given = motions->count() > 0;
    a->robots_given = robots->count() > 0;
    experiment(*a);
  });
}

}  // namespace stiffpath::cli
