// `stiffpath fit`: fit a compliance model to a displacement table and write the model file.
#include <fmt/format.h>
#include <memory>

#include "commands.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::cli {

namespace {
struct FitOptions {
  std::string data = "thesis";
  std::string mechanism = "oc";
  std::string method = "bilinear";
  std::string forces = "measured";
  std::string outside = "clamp";
  std::string zero_force = "relative";
  std::string output;
  bool json = false;
};

void run(const FitOptions& o) {
  const auto table = measurement::load_displacement_table(o.data);
  auto fitted = compliance::fit_model(table, resolve_build(o.mechanism), o.method,
                                      compliance::parse_force_convention(o.forces));
  fitted.model->set_outside_policy(compliance::parse_outside_policy(o.outside));
  fitted.model->set_zero_force(compliance::parse_zero_force(o.zero_force));
  const nlohmann::json doc = compliance::model_to_json(*fitted.model, fitted.provenance);
  if (!o.output.empty()) compliance::save_model(o.output, *fitted.model, fitted.provenance);
  if (o.json) {
    print_json(doc);
    return;
  }
  fmt::print("{} model of {} from {} ({} forces, {}, outside grid: {})\n", fitted.model->method(),
             fitted.provenance.mechanism, fitted.provenance.source, o.forces, o.zero_force, o.outside);
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
  if (!o.output.empty()) fmt::print("wrote {}\n", o.output);
}
}  // namespace

void add_fit_command(CLI::App& app) {
  auto o = std::make_shared<FitOptions>();
  auto* cmd = app.add_subcommand("fit", "Fit a compliance model (thesis eqs. 4.8-4.12, or a better one) to a table");
  cmd->add_option("data", o->data, "Displacement table CSV, or 'thesis' for the built-in data set")->capture_default_str();
  cmd->add_option("--mechanism", o->mechanism, "oc, sc, or a preset/file whose build selects the rows")->capture_default_str();
  cmd->add_option("--method", o->method, "bilinear (thesis), symmetric, physical, physical-0, physical-2")
      ->capture_default_str();
  cmd->add_option("--forces", o->forces, "measured (kgf relative to step 0) or nominal (50-250 N)")->capture_default_str();
  cmd->add_option("--outside", o->outside, "Outside the grid: clamp, extrapolate or error")->capture_default_str();
  cmd->add_option("--zero-force", o->zero_force, "relative (default) or thesis-raw (keep eq. 4.8's intercepts)")
      ->capture_default_str();
  cmd->add_option("-o,--output", o->output, "Write the model file (JSON)");
  cmd->add_flag("--json", o->json, "Print the model document");
  cmd->callback([o] { run(*o); });
}

}  // namespace stiffpath::cli
