// Entry point of the stiffpath CLI: registers subcommands, maps errors to exit codes (2 bad input, 1 internal).
#include <cmath>
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::cli {

void print_json(const nlohmann::json& document) { std::cout << document.dump(2) << '\n'; }

double tidy(double value) {
  if (value == 0.0 || !std::isfinite(value)) return value;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.12g", value);
  return std::strtod(buffer, nullptr);
}

}  // namespace stiffpath::cli

int main(int argc, char** argv) {
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
  stiffpath::cli::add_data_command(app);
  stiffpath::cli::add_repeatability_command(app);
  stiffpath::cli::add_scan_command(app);
  stiffpath::cli::add_render_scan_command(app);
  stiffpath::cli::add_simulate_command(app);
  stiffpath::cli::add_experiment_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const stiffpath::Error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
