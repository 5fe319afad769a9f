// Registration functions of the CLI's subcommands (one source file each) and shared output helpers.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace stiffpath::cli {

void add_kin_command(CLI::App& app);
void add_mechanism_command(CLI::App& app);
void add_mobility_command(CLI::App& app);
void add_fit_command(CLI::App& app);
void add_predict_command(CLI::App& app);
void add_cv_command(CLI::App& app);
void add_plot_command(CLI::App& app);
void add_plan_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_measure_command(CLI::App& app);
void add_campaign_command(CLI::App& app);
void add_geometry_command(CLI::App& app);
void add_data_command(CLI::App& app);
void add_repeatability_command(CLI::App& app);
void add_scan_command(CLI::App& app);
void add_render_scan_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_experiment_command(CLI::App& app);
void add_report_command(CLI::App& app);
void add_linuxcnc_command(CLI::App& app);
void add_calibrate_command(CLI::App& app);
//! `calibrate fit`, in stiffpath-vision (it reads the scan).
void add_calibrate_fit_command(CLI::App& app);
//! Replaces this process with stiffpath-vision running `words` (the subcommand and its arguments); returns only by
//! throwing when that program cannot be started.
[[noreturn]] void run_vision_tool(const std::vector<std::string>& words);

//! A JSON document as text (two-space indent; text that is not UTF-8 printed with U+FFFD in its place).
std::string dump_json(const nlohmann::json& document);
//! Prints a JSON document on stdout (dump_json, newline).
void print_json(const nlohmann::json& document);

//! Rounds for display in JSON so that outputs are stable (12 significant digits).
double tidy(double value);

//! With --json, this subcommand's errors are printed as one JSON document on stderr
//! ({"errors": [{"file", "line", "column", "message"}], "omitted": N}) instead of "error: …" lines.
void enable_json_errors(const CLI::App* command);

}  // namespace stiffpath::cli
