// `stiffpath predict`: the deflection a robot's compliance model predicts at a point under a force.
#include <fmt/format.h>
#include <cmath>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "robot_flags.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/compliance/tool_point.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::cli {

namespace {
struct PredictOptions {
  std::string robot;
  ModelFlags model;
  std::string outside;
  double x_mm = 0.0, y_mm = 0.0, fx_n = 0.0, fy_n = 0.0;
  double tool_below_G_mm = 0.0;
  bool tool = false;
  std::string angles;  // default: the table the model was fitted to
  bool json = false;
};

void run(const PredictOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  auto loaded = compliance::load_robot_model(robot, model_request(o.model));
  if (!o.outside.empty()) loaded.model->set_outside_policy(core::parse_enum<compliance::OutsidePolicy>(o.outside));
  const compliance::Model& model = *loaded.model;
  const compliance::Vec2 p{o.x_mm * 1e-3, o.y_mm * 1e-3}, F{o.fx_n, o.fy_n};
  if (model.refuses(p)) {
    const auto b = model.bounds();
    throw Error(fmt::format("point ({}, {}) mm is more than {:g} mm outside the measured region of model {}, x [{:.3f}, "
                            "{:.3f}] mm, y [{:.3f}, {:.3f}] mm (use --outside clamp or extrapolate)",
                            o.x_mm, o.y_mm, compliance::kOutsideMargin_m * 1e3, loaded.label, b.x_min * 1e3,
                            b.x_max * 1e3, b.y_min * 1e3, b.y_max * 1e3));
  }
  const compliance::Vec2 d = model.predict(p, F);
  const compliance::Mat2 c = model.compliance(p) * 1e6;
  nlohmann::json out = {{"robot", robot.name},
                        {"model", loaded.label},
                        {"method", model.description()},
                        {"x_mm", o.x_mm},
                        {"y_mm", o.y_mm},
                        {"fx_n", o.fx_n},
                        {"fy_n", o.fy_n},
                        {"dx_um", tidy(d.x() * 1e6)},
                        {"dy_um", tidy(d.y() * 1e6)},
                        {"inside_grid", model.inside(p)},
                        {"C_um_per_N", {{tidy(c(0, 0)), tidy(c(0, 1))}, {tidy(c(1, 0)), tidy(c(1, 1))}}}};
  // The prediction's uncertainty: the model file's, or learnt now from the table the model was fitted to.
  std::string no_band;
  try {
    compliance::add_uncertainty(loaded);
  } catch (const Error& e) {
    no_band = e.message();
  }
  if (loaded.provenance.uncertainty) {
    const auto& u = *loaded.provenance.uncertainty;
    const compliance::Mat2 cov = u.deflection_covariance(p, F), meas = u.measurement_covariance(p, F);
    const double k = u.band_factor();
    out["dx_sigma_um"] = tidy(std::sqrt(cov(0, 0)) * 1e6);
    out["dy_sigma_um"] = tidy(std::sqrt(cov(1, 1)) * 1e6);
    out["dx_band_95_um"] = tidy(k * std::sqrt(cov(0, 0)) * 1e6);
    out["dy_band_95_um"] = tidy(k * std::sqrt(cov(1, 1)) * 1e6);
    out["measured_dx_band_95_um"] = tidy(k * std::sqrt(meas(0, 0)) * 1e6);
    out["measured_dy_band_95_um"] = tidy(k * std::sqrt(meas(1, 1)) * 1e6);
    out["uncertainty_basis"] = compliance::to_string(u.basis);
  } else {
    out["uncertainty"] = "unknown: " + no_band;
  }
  if (o.tool) {
    const core::DataRef angles_ref = !o.angles.empty() ? table_ref(o.angles) : robot.compliance.table;
    if (angles_ref.empty()) throw Error("--tool-below-g-mm needs a table with rx_deg, ry_deg: give --angles");
    const auto table = measurement::load_displacement_table(angles_ref).filter(loaded.provenance.rows);
    std::shared_ptr<const compliance::GridModel> angular =
        compliance::make_angular_model(compliance::fit_points(table, loaded.provenance.convention), table.source);
    std::shared_ptr<const compliance::Model> at_G = compliance::load_robot_model(robot, model_request(o.model)).model;
    const compliance::ToolPointModel tool(at_G, angular, o.tool_below_G_mm * 1e-3);
    const compliance::Vec2 dt = tool.predict(p, F);
    out["tool_below_G_mm"] = o.tool_below_G_mm;
    out["tool_dx_um"] = tidy(dt.x() * 1e6);
    out["tool_dy_um"] = tidy(dt.y() * 1e6);
    out["tool_change_um"] = tidy((dt - d).norm() * 1e6);
  }
  if (o.json) {
    print_json(out);
    return;
  }
  fmt::print("{} ({}) of robot {} at ({}, {}) mm under F = ({}, {}) N{}:\n", loaded.label, model.description(), robot.name,
             o.x_mm, o.y_mm, o.fx_n, o.fy_n,
             model.inside(p) ? "" : fmt::format(" [outside the measured region: {}]", compliance::outside_words(model.outside_policy())));
  fmt::print("  dx = {:.2f} um, dy = {:.2f} um at G\n", d.x() * 1e6, d.y() * 1e6);
  if (out.contains("dx_band_95_um")) {
    fmt::print("  95 % band of the deflection: dx +- {:.2f} um, dy +- {:.2f} um; of a measurement of it (the campaign's "
               "scatter added): +- {:.2f} um, +- {:.2f} um\n",
               out["dx_band_95_um"].get<double>(), out["dy_band_95_um"].get<double>(),
               out["measured_dx_band_95_um"].get<double>(), out["measured_dy_band_95_um"].get<double>());
  } else {
    fmt::print("  uncertainty unknown: {}\n", no_band);
  }
  fmt::print("  C = [{:.4f} {:.4f}; {:.4f} {:.4f}] um/N\n", c(0, 0), c(0, 1), c(1, 0), c(1, 1));
  if (o.tool) {
    fmt::print("  tool point {} mm below G: dx = {:.2f} um, dy = {:.2f} um (changes the prediction by {:.2f} um)\n",
               o.tool_below_G_mm, out["tool_dx_um"].get<double>(), out["tool_dy_um"].get<double>(),
               out["tool_change_um"].get<double>());
  }
}
}  // namespace

void add_predict_command(CLI::App& app) {
  auto o = std::make_shared<PredictOptions>();
  auto* cmd = app.add_subcommand("predict", "Predict the deflection at a point under a force (eqs. 4.6-4.7)");
  add_robot_flag(cmd, o->robot);
  add_model_flags(cmd, o->model);
  cmd->add_option("--outside", o->outside, "Beyond the measured region: error, clamp or extrapolate (default: model's)");
  cmd->add_option("--x-mm", o->x_mm, "Platform x (mm)")->required()->check(within(-1e4, 1e4, "mm"));
  cmd->add_option("--y-mm", o->y_mm, "Platform y (mm)")->required()->check(within(-1e4, 1e4, "mm"));
  cmd->add_option("--fx-n", o->fx_n, "Force along x (N)")->required()->check(within(-1e6, 1e6, "N"));
  cmd->add_option("--fy-n", o->fy_n, "Force along y (N)")->required()->check(within(-1e6, 1e6, "N"));
  auto* tool = cmd->add_option("--tool-below-g-mm", o->tool_below_G_mm,
                               "Also predict at a tool point this far below G, using the angular deflections")
                   ->check(within(-1e3, 1e3, "mm"));
  cmd->add_option("--angles", o->angles, "Table with rx_deg, ry_deg for --tool-below-g-mm (default: the robot's)");
  cmd->add_flag("--json", o->json, "Print JSON (keys dx_um, dy_um, ...)");
  cmd->callback([o, tool] {
    o->tool = tool->count() > 0;
    run(*o);
  });
}

}  // namespace stiffpath::cli
