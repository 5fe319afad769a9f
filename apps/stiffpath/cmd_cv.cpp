// `stiffpath cv`: leave-one-out cross-validation of every compliance model on one mechanism's data.
#include <fmt/format.h>
#include <memory>

#include "commands.hpp"
#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::cli {

namespace {
struct CvOptions {
  std::string data = "thesis";
  std::string mechanism = "oc";
  std::string forces = "measured";
  std::string zero_force = "relative";
  double link_length_mm = 150.0;
  bool json = false;
};

nlohmann::json to_json(const compliance::CvReport& r) {
  nlohmann::json methods = nlohmann::json::array();
  for (const auto& m : r.methods) {
    nlohmann::json points = nlohmann::json::array();
    for (const auto& p : m.points) {
      nlohmann::json pj = {{"point", p.id}, {"predicted", p.predicted}, {"interior", p.interior}};
      if (p.predicted) {
        pj["error_um"] = tidy(p.mean_abs_error_um);
        pj["vector_error_um"] = tidy(p.mean_vector_error_um);
      }
      points.push_back(pj);
    }
    methods.push_back({{"method", m.method},
                       {"description", m.description},
                       {"predicted_points", m.predicted},
                       {"mean_error_um", tidy(m.mean_um)},
                       {"max_error_um", tidy(m.max_um)},
                       {"interior_mean_error_um", tidy(m.interior_mean_um)},
                       {"points", points}});
  }
  return {{"source", r.source},
          {"mechanism", r.mechanism},
          {"force_convention", compliance::to_string(r.convention)},
          {"zero_force", compliance::to_string(r.zero_force)},
          {"error_definition", "mean of |dx error| and |dy error| over the highest load step of each load direction"},
          {"methods", methods}};
}

void run(const CvOptions& o) {
  const auto table = measurement::load_displacement_table(o.data);
  const std::string build = resolve_build(o.mechanism);
  const auto rows = table.filter(build);
  if (rows.rows.empty()) throw Error(SourceLocation{table.source}, "no rows for mechanism " + build);
  const auto convention = compliance::parse_force_convention(o.forces);
  auto report = compliance::cross_validate(compliance::group_by_point(rows, convention), o.link_length_mm * 1e-3,
                                           table.source, compliance::parse_zero_force(o.zero_force));
  report.mechanism = build;
  report.convention = convention;
  if (o.json) {
    print_json(to_json(report));
    return;
  }
  fmt::print("leave-one-out cross-validation, {} from {}: error = mean |dx|,|dy| error at the highest load (um)\n",
             build, table.source);
  fmt::print("{:<12} {:>9} {:>14} {:>10} {:>8}\n", "method", "interior", "all predicted", "max", "points");
  for (const auto& m : report.methods) {
    fmt::print("{:<12} {:>9.1f} {:>14.1f} {:>10.1f} {:>8}\n", m.method, m.interior_mean_um, m.mean_um, m.max_um,
               m.predicted);
  }
  fmt::print("interior = points off the grid's boundary (x2y2, x2y3, x2y4 on the thesis grid)\n");
}
}  // namespace

void add_cv_command(CLI::App& app) {
  auto o = std::make_shared<CvOptions>();
  auto* cmd = app.add_subcommand("cv", "Leave-one-out cross-validation of every compliance model");
  cmd->add_option("data", o->data, "Displacement table CSV, or 'thesis'")->capture_default_str();
  cmd->add_option("--mechanism", o->mechanism, "oc or sc (or a preset/file)")->capture_default_str();
  cmd->add_option("--forces", o->forces, "measured or nominal")->capture_default_str();
  cmd->add_option("--zero-force", o->zero_force, "relative or thesis-raw")->capture_default_str();
  cmd->add_option("--link-length-mm", o->link_length_mm, "Five-bar link length for the physical model")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON");
  cmd->callback([o] { run(*o); });
}

}  // namespace stiffpath::cli
