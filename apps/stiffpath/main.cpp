// Entry point of the stiffpath CLI: registers subcommands, maps errors to exit codes (2 bad input, 1 internal).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <set>
#include <sstream>

#include "commands.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/signal_cleanup.hpp"
#include "stiffpath/motion/gcode_diagnostics.hpp"

namespace stiffpath::cli {

// Text that is not UTF-8 (a file name, a CSV cell) is printed with U+FFFD in its place, never refused.
void print_json(const nlohmann::json& document) {
  std::cout << document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
}

double tidy(double value) {
  if (value == 0.0 || !std::isfinite(value)) return value;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.12g", value);
  return std::strtod(buffer, nullptr);
}

namespace {

std::set<const CLI::App*>& json_error_commands() {
  static std::set<const CLI::App*> commands;
  return commands;
}

// Whether a subcommand that ran (or one of its own) prints its errors as JSON and was given --json.
bool json_requested(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) {
    const CLI::Option* json = sub->get_option_no_throw("--json");
    if ((json_error_commands().contains(sub) && json != nullptr && json->count() > 0) || json_requested(*sub)) return true;
  }
  return false;
}

nlohmann::json error_json(const stiffpath::Error& e) {
  const auto& w = e.where();
  return {{"file", w.file.empty() ? nlohmann::json(nullptr) : nlohmann::json(w.file)},
          {"line", w.line > 0 ? nlohmann::json(w.line) : nlohmann::json(nullptr)},
          {"column", w.column > 0 ? nlohmann::json(w.column) : nlohmann::json(nullptr)},
          {"message", e.message()}};
}

// Bad input: "error: " before each line of the message, or with --json one document on stderr:
// {"errors": [{"file", "line", "column", "message"}, …], "omitted": N}.
void report(const CLI::App& app, const stiffpath::Error& e) {
  const auto* all = dynamic_cast<const stiffpath::motion::GcodeErrors*>(&e);
  if (json_requested(app)) {
    nlohmann::json errors = nlohmann::json::array();
    if (all != nullptr) {
      for (const auto& one : all->errors()) errors.push_back(error_json(one));
    } else {
      errors.push_back(error_json(e));
    }
    std::cerr << nlohmann::json{{"errors", errors}, {"omitted", all != nullptr ? all->omitted() : 0}}.dump(
                     2, ' ', false, nlohmann::json::error_handler_t::replace)
              << '\n';
    return;
  }
  std::istringstream lines(e.what());
  for (std::string line; std::getline(lines, line);) std::cerr << "error: " << line << '\n';
}

}  // namespace

void enable_json_errors(const CLI::App* command) { json_error_commands().insert(command); }

}  // namespace stiffpath::cli

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
  stiffpath::cli::add_data_command(app);
  stiffpath::cli::add_repeatability_command(app);
  stiffpath::cli::add_scan_command(app);
  stiffpath::cli::add_render_scan_command(app);
  stiffpath::cli::add_simulate_command(app);
  stiffpath::cli::add_experiment_command(app);
  stiffpath::cli::add_report_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const stiffpath::Error& e) {
    stiffpath::cli::report(app, e);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
