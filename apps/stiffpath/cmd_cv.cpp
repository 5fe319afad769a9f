// `stiffpath cv`: leave-one-out cross-validation of every compliance model that can run on a robot's data.
#include <fmt/format.h>
#include <memory>

#include "commands.hpp"
#include "robot_flags.hpp"
#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::cli {

namespace {
struct CvOptions {
  std::string data;
  std::string robot;
  std::string rows;
  bool rows_given = false;
  std::string forces = "measured";
  std::string zero_force = "relative";
  bool json = false;
};

nlohmann::json to_json(const compliance::CvReport& r, compliance::FitMethod favoured,
                       const std::vector<std::pair<compliance::FitMethod, double>>& scores) {
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
    double common = 0.0;
    for (const auto& [name, score] : scores) {
      if (name == m.method) common = score;
    }
    nlohmann::json band = {{"cells", m.band_cells}, {"inside", m.inside_band}, {"mean_half_width_um", tidy(m.mean_band_um)},
                           {"fraction", m.band_cells > 0 ? tidy(static_cast<double>(m.inside_band) / m.band_cells) : 0.0}};
    methods.push_back({{"band_95", band},
                       {"method", core::enum_name(m.method)},
                       {"description", m.description},
                       {"predicted_points", m.predicted},
                       {"mean_error_um", tidy(m.mean_um)},
                       {"max_error_um", tidy(m.max_um)},
                       {"interior_mean_error_um", tidy(m.interior_mean_um)},
                       {"common_points_mean_error_um", tidy(common)},
                       {"points", points}});
  }
  nlohmann::json skipped = nlohmann::json::array();
  for (const auto& s : r.skipped) skipped.push_back({{"method", core::enum_name(s.method)}, {"reason", s.reason}});
  return {{"source", r.source},
          {"rows", r.rows},
          {"robot", r.robot},
          {"force_convention", core::enum_name(r.convention)},
          {"zero_force", core::enum_name(r.zero_force)},
          {"error_definition", "mean of |dx error| and |dy error| over the highest load step of each load direction"},
          {"favoured_method", core::enum_name(favoured)},
          {"methods", methods},
          {"could_not_run", skipped}};
}

void run(const CvOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  if (o.data.empty() && robot.compliance.table.empty()) {
    throw Error(fmt::format("robot '{}' names no displacement table: give one as the first argument", robot.name));
  }
  const auto table = measurement::load_displacement_table(o.data.empty() ? robot.compliance.table : table_ref(o.data));
  const std::string rows_name = o.rows_given ? o.rows : robot.compliance.rows;
  const auto rows = table.filter(rows_name);
  if (rows.rows.empty()) throw Error(SourceLocation{table.source}, "no rows with mechanism '" + rows_name + "'");
  const auto convention = core::parse_enum<compliance::ForceConvention>(o.forces);
  auto report = compliance::cross_validate(compliance::group_by_point(rows, convention), robot.geometry, table.source,
                                           core::parse_enum<compliance::ZeroForce>(o.zero_force), true);
  report.rows = rows_name;
  report.robot = robot.name;
  report.convention = convention;
  std::vector<std::pair<compliance::FitMethod, double>> scores;
  const compliance::FitMethod favoured = compliance::favoured_method(report, &scores);
  if (o.json) {
    print_json(to_json(report, favoured, scores));
    return;
  }
  fmt::print("leave-one-out cross-validation, robot {}, {}{}: error = mean |dx|,|dy| error at the highest load (um)\n",
             robot.name, table.source, rows_name.empty() ? "" : " rows " + rows_name);
  fmt::print("{:<16} {:>9} {:>14} {:>10} {:>8} {:>14} {:>16} {:>11}\n", "method", "interior", "all predicted", "max", "points",
             "common points", "in 95 % band", "band +-um");
  for (std::size_t k = 0; k < report.methods.size(); ++k) {
    const auto& m = report.methods[k];
    fmt::print("{:<16} {:>9.1f} {:>14.1f} {:>10.1f} {:>8} {:>14.1f} {:>16} {:>11}\n", core::enum_name(m.method), m.interior_mean_um, m.mean_um,
               m.max_um, m.predicted, scores[k].second,
               m.band_cells > 0 ? fmt::format("{}/{} {:.0f} %", m.inside_band, m.band_cells, 100.0 * m.inside_band / m.band_cells)
                                : std::string("-"),
               m.band_cells > 0 ? fmt::format("{:.1f}", m.mean_band_um) : std::string("-"));
  }
  for (const auto& s : report.skipped) fmt::print("{:<16} could not run: {}\n", core::enum_name(s.method), s.reason);
  const auto& named = robot.compliance;
  const std::string note = !named.model.empty()    ? fmt::format("; robot {} names its model file {}", robot.name, named.model.label())
                           : named.method ? fmt::format("; robot {} names the method {} in its file", robot.name, core::enum_name(*named.method))
                                                   : fmt::format("; robot {} uses it", robot.name);
  fmt::print("interior = points strictly inside the points' bounding rectangle; common points = those every method "
             "predicts;\nin 95 % band = held-out dx, dy cells within the 95 % band the method states for a measurement, "
             "learnt from the other points;\nband +-um = its mean half-width\nfavoured: {} (what fit chooses without --method{})\n",
             core::enum_name(favoured), note);
}
}  // namespace

void add_cv_command(CLI::App& app) {
  auto o = std::make_shared<CvOptions>();
  auto* cmd = app.add_subcommand("cv", "Leave-one-out cross-validation of every compliance model that can run");
  cmd->add_option("data", o->data, "Displacement table CSV, or 'thesis' (default: the robot's own table)");
  add_robot_flag(cmd, o->robot);
  auto* rows = cmd->add_option("--rows", o->rows, "Rows of the table's mechanism column (default: the robot's)");
  cmd->add_option("--forces", o->forces, "measured or nominal")->capture_default_str();
  cmd->add_option("--zero-force", o->zero_force, "relative or thesis-raw")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON");
  cmd->callback([o, rows] {
    o->rows_given = rows->count() > 0;
    run(*o);
  });
}

}  // namespace stiffpath::cli
