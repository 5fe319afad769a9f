// What both CLI programs (stiffpath, stiffpath-vision) share: parsing, error reports, exit codes (2 bad input, 1 internal).
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <set>
#include <sstream>

#include "cli_run.hpp"
#include "commands.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/motion/gcode_diagnostics.hpp"

namespace stiffpath::cli {

// Text that is not UTF-8 (a file name, a CSV cell) is printed with U+FFFD in its place, never refused.
std::string dump_json(const nlohmann::json& document) {
  return document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

void print_json(const nlohmann::json& document) { std::cout << dump_json(document) << '\n'; }

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

namespace {
// Flushes both standard output streams; false when a write failed (a full disk, /dev/full, a closed pipe).
bool flush_standard_output() {
  std::cout.flush();
  const bool ok = static_cast<bool>(std::cout);
  return std::fflush(stdout) == 0 && std::ferror(stdout) == 0 && ok;
}

int run_command(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const stiffpath::Error& e) {
    report(app, e);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace

int run(CLI::App& app, int argc, char** argv) {
  const int status = run_command(app, argc, argv);
  if (!flush_standard_output()) {
    const int error = errno;
    std::cerr << "error: standard output: write failed (" << std::strerror(error) << "): what was printed is incomplete\n";
    return 2;
  }
  return status;
}

}  // namespace stiffpath::cli
