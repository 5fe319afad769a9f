// `stiffpath fit`: fit a compliance model to a robot's displacement table and write the model file.
#include <fmt/format.h>
#include <cmath>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "robot_flags.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::cli {

namespace {
struct FitOptions {
  std::string data;  // default: the robot's table
  std::string robot;
  std::string rows;  // default: the robot's rows
  bool rows_given = false;
  std::string method = "auto";
  std::string forces = "measured";
  std::string outside = "error";
  std::string zero_force = "relative";
  std::string output;
  bool json = false;
};

void run(const FitOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  if (o.data.empty() && robot.compliance.table.empty()) {
    throw Error(fmt::format("robot '{}' names no displacement table: give one as the first argument", robot.name));
  }
  const core::DataRef table_file = o.data.empty() ? robot.compliance.table : table_ref(o.data);
  core::check_distinct_files(robot_inputs(robot, false, {{"data", table_file.builtin ? "" : table_file.path}}),
                             {{"-o", o.output}});
  const auto table = measurement::load_displacement_table(table_file);
  const std::string rows = o.rows_given ? o.rows : robot.compliance.rows;
  const auto method = [&] {
    try {
      return compliance::parse_fit_method(o.method);
    } catch (const Error& e) {
      throw Error("--method: " + e.message());
    }
  }();
  auto fitted = compliance::fit_model(table, rows, method, core::parse_enum<compliance::ForceConvention>(o.forces), robot);
  fitted.model->set_outside_policy(core::parse_enum<compliance::OutsidePolicy>(o.outside));
  fitted.model->set_zero_force(core::parse_enum<compliance::ZeroForce>(o.zero_force));
  std::string uncertainty_note;
  try {
    compliance::add_uncertainty(fitted);
  } catch (const Error& e) {
    uncertainty_note = "no prediction uncertainty: " + e.message();
  }
  const nlohmann::json doc = compliance::model_to_json(*fitted.model, fitted.provenance);
  if (!o.output.empty()) compliance::save_model(o.output, *fitted.model, fitted.provenance);
  if (o.json) {
    print_json(doc);
    return;
  }
  fmt::print("{} model of robot {} from {}{} ({} forces, {}, beyond the measured region: {})\n", fitted.model->description(),
             robot.name, fitted.provenance.source, rows.empty() ? "" : " rows " + rows, o.forces, o.zero_force,
             compliance::outside_words(fitted.model->outside_policy()));
  if (fitted.provenance.selected_by == compliance::MethodSelection::cross_validation) {
    std::string scores;
    for (const auto& [name, um] : fitted.provenance.selection["mean_error_um"].items()) {
      scores += fmt::format("{}{} {:.1f}", scores.empty() ? "" : ", ", name, um.get<double>());
    }
    fmt::print("method chosen by leave-one-out cross-validation (mean error in um on the points all predict): {}\n",
               scores);
    for (const auto& [name, why] : fitted.provenance.selection["could_not_run"].items()) {
      fmt::print("  {} could not run: {}\n", name, why.get<std::string>());
    }
  }
  if (doc.contains("nodes")) {
    fmt::print("{:>6} {:>9} {:>7} {:>9} {:>9} {:>9} {:>9}   (C in um/N)\n", "point", "x_mm", "y_mm", "Cxx", "Cxy", "Cyx",
               "Cyy");
    for (const auto& n : doc["nodes"]) {
      const auto& c = n["C_um_per_N"];
      fmt::print("{:>6} {:>9.3f} {:>7.1f} {:>9.4f} {:>9.4f} {:>9.4f} {:>9.4f}\n", n["point"].get<std::string>(),
                 n["x_mm"].get<double>(), n["y_mm"].get<double>(), c[0][0].get<double>(), c[0][1].get<double>(),
                 c[1][0].get<double>(), c[1][1].get<double>());
    }
  } else {
    fmt::print("D(p) coefficients (um/N): {}\nfit: {}\n", doc["D_um_per_N"].dump(), doc["stats"].dump());
  }
  if (fitted.provenance.uncertainty) {
    const auto& u = *fitted.provenance.uncertainty;
    fmt::print("prediction uncertainty ({} basis, learnt from {} leave-one-out predictions; 95 % band = {:.2f} sigma): "
               "C entries' floor {:.3f} um/N rms, a measurement's scatter about C.F {:.1f} / {:.1f} um (x / y)\n",
               compliance::to_string(u.basis), u.held_out, u.band_factor(),
               std::sqrt((u.floor_m2_per_N2[0] + u.floor_m2_per_N2[1] + u.floor_m2_per_N2[2] + u.floor_m2_per_N2[3]) / 4) * 1e6,
               u.campaign_sigma_m.x() * 1e6, u.campaign_sigma_m.y() * 1e6);
  } else {
    fmt::print("{}\n", uncertainty_note);
  }
  if (!o.output.empty()) fmt::print("wrote {}\n", o.output);
}
}  // namespace

void add_fit_command(CLI::App& app) {
  auto o = std::make_shared<FitOptions>();
  auto* cmd = app.add_subcommand("fit", "Fit a compliance model (thesis eqs. 4.8-4.12, or a better one) to a robot's table");
  cmd->add_option("data", o->data, "Displacement table CSV, or 'thesis' (default: the robot's own table)");
  add_robot_flag(cmd, o->robot);
  auto* rows = cmd->add_option("--rows", o->rows, "Rows of the table's mechanism column to use (default: the robot's)");
  cmd->add_option("--method", o->method,
                  "auto (the method cross-validation favours), or one of " + core::enum_choices<compliance::FitMethod>() +
                      " (bilinear: the thesis's)")
      ->capture_default_str();
  cmd->add_option("--forces", o->forces, "measured (the table's F_N, relative to step 0) or nominal (its F_nominal_N column: the round loads it names)")->capture_default_str();
  cmd->add_option("--outside", o->outside,
                  "Beyond 1 mm outside the measured region: error (refuse), clamp or extrapolate")->capture_default_str();
  cmd->add_option("--zero-force", o->zero_force, "relative (default) or thesis-raw (keep eq. 4.8's intercepts)")
      ->capture_default_str();
  cmd->add_option("-o,--output", o->output, "Write the model file (JSON)")->check(output_name());
  cmd->add_flag("--json", o->json, "Print the model document");
  cmd->callback([o, rows] {
    o->rows_given = rows->count() > 0;
    run(*o);
  });
}

}  // namespace stiffpath::cli
