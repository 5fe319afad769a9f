// Entry point of the stiffpath CLI: registers the subcommands and runs the one named.
#include "cli_run.hpp"
#include "commands.hpp"
#include "stiffpath/core/signal_cleanup.hpp"

int main(int argc, char** argv) {
  stiffpath::core::install_signal_cleanup();  // an interrupted run leaves no temporary file
  CLI::App app{"stiffpath: compliance compensation for high-acceleration planar parallel robots"};
  app.set_version_flag("--version", std::string("stiffpath ") + STIFFPATH_VERSION);
  app.require_subcommand(1);
  stiffpath::cli::add_kin_command(app);
  stiffpath::cli::add_mechanism_command(app);
  stiffpath::cli::add_mobility_command(app);
  stiffpath::cli::add_fit_command(app);
  stiffpath::cli::add_predict_command(app);
  stiffpath::cli::add_cv_command(app);
  stiffpath::cli::add_plot_command(app);
  stiffpath::cli::add_plan_command(app);
  stiffpath::cli::add_run_command(app);
  stiffpath::cli::add_measure_command(app);
  stiffpath::cli::add_campaign_command(app);
  stiffpath::cli::add_geometry_command(app);
  stiffpath::cli::add_data_command(app);
  stiffpath::cli::add_repeatability_command(app);
  stiffpath::cli::add_vision_commands(app);  // scan, render-scan: run by stiffpath-vision
  stiffpath::cli::add_simulate_command(app);
  stiffpath::cli::add_experiment_command(app);
  stiffpath::cli::add_report_command(app);
  stiffpath::cli::add_linuxcnc_command(app);
  stiffpath::cli::add_calibrate_command(app);
  return stiffpath::cli::run(app, argc, argv);
}
