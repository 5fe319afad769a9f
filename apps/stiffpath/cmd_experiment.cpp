// `stiffpath experiment`: the thesis's test matrix (§4.5) on the digital twin, with CSV, summary and figures.
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <memory>

#include "commands.hpp"
#include "progress.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/report/experiment_plots.hpp"
#include "stiffpath/report/gnuplot.hpp"
#include "stiffpath/simulation/experiment.hpp"

namespace stiffpath::cli {

namespace {
struct ExperimentArgs {
  std::string output = "experiment";
  simulation::ExperimentOptions options;
  std::vector<std::string> paths;
  bool motions_given = false;
  bool no_plots = false, quiet = false;
  std::string style = "screen";
};

void experiment(ExperimentArgs a) {
  for (const auto& path : a.paths) a.options.paths.push_back(simulation::user_motion(path));
  if (!a.paths.empty() && !a.motions_given) a.options.motions.clear();  // only the user's paths
  const auto start = std::chrono::steady_clock::now();
  const auto style = report::parse_style(a.style);
  Progress progress("experiment", a.quiet);
  const auto results = simulation::run_experiment(a.options, progress.callback());
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::filesystem::path dir(a.output);
  std::filesystem::create_directories(dir);
  core::write_file_atomically(dir / "results.csv", simulation::experiment_csv(results));
  const std::string summary = simulation::experiment_summary(results);
  core::write_file_atomically(dir / "summary.md", summary);
  fmt::print("{} runs in {:.2f} s → {}\n\n{}", results.size(), seconds, (dir / "results.csv").string(), summary);
  if (!a.no_plots) {
    if (!report::gnuplot_available()) {
      fmt::print("\ngnuplot not found: figures skipped\n");
      return;
    }
    const auto figures_dir = dir / "figures";
    std::filesystem::create_directories(figures_dir);
    const auto figures = report::write_results_figures(figures_dir, report::results_from_runs(results), style);
    fmt::print("\nfigures ({}, SVG, PNG, gnuplot script and data each): {}\n", figures_dir.string(),
               fmt::join(figures, ", "));
  }
}
}  // namespace

void add_experiment_command(CLI::App& app) {
  auto a = std::make_shared<ExperimentArgs>();
  auto* cmd = app.add_subcommand("experiment", "The thesis's test matrix on the digital twin of robots (figs. 4.9-4.11)");
  cmd->add_option("-o,--output", a->output, "Output directory (results.csv, summary.md, figures/)")->capture_default_str();
  cmd->add_option("--robots,--robot,--mechanisms", a->options.robots, "Presets or robot files to run")
      ->capture_default_str();
  auto* motions = cmd->add_option("--motions", a->options.motions,
                                  "x, y, triangle: placed in each robot's measured rectangle")->capture_default_str();
  cmd->add_option("--path", a->paths, "A G-code file of your own to run as FILE[:SIDES] (repeatable; without "
                                      "--motions only these run)");
  cmd->add_option("--accelerations-g", a->options.accelerations_g, "Acceleration limits (g)")
      ->check(CLI::Range(0.1, 10.0))->capture_default_str();
  cmd->add_option("--perturbation", a->options.truth.perturbation, "Relative perturbation of C_true")
      ->check(CLI::Range(0.0, 0.5))->capture_default_str();
  cmd->add_option("--gain", a->options.compensator.gain, "Compensation gain")->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--damping-ratio", a->options.simulation.plant.tip_damping_ratio, "Damping ratio of the tip's modes")
      ->check(CLI::Range(0.0, 2.0))->capture_default_str();
  cmd->add_flag("--no-plots", a->no_plots, "Skip the gnuplot figures");
  cmd->add_option("--style", a->style, "Figures for the screen (colour) or paper (black and white, larger fonts)")
      ->check(CLI::IsMember({"screen", "paper"}))->capture_default_str();
  cmd->add_flag("--quiet", a->quiet, "No progress bar (it is shown only on a terminal anyway)");
  cmd->callback([a, motions] {
    a->motions_given = motions->count() > 0;
    experiment(*a);
  });
}

}  // namespace stiffpath::cli
