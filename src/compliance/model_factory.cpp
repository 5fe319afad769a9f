// Fitting models by method name (or the one cross-validation favours), the built-in thesis models, and a robot's own model.
#include "stiffpath/compliance/model_factory.hpp"

#include <fmt/format.h>

#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/fit_budget.hpp"
#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/compliance/model_check.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/compliance/physical_model.hpp"
#include "stiffpath/compliance/physical_spline_model.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

std::optional<FitMethod> parse_fit_method(std::string_view text) {
  if (text == "auto") return std::nullopt;
  if (const auto method = core::find_enum<FitMethod>(text)) return method;
  throw Error(fmt::format("compliance method must be auto, {}, got '{}'", core::enum_choices<FitMethod>(), text));
}

namespace {
std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

std::string short_hash(const kinematics::FiveBarGeometry& g) { return kinematics::geometry_hash(g).substr(0, 12); }
}  // namespace

LoadedModel fit_model(const measurement::DisplacementTable& table, const std::string& rows,
                      std::optional<FitMethod> method, ForceConvention convention, const kinematics::Robot& robot) {
  const auto selected = table.filter(rows);
  if (selected.rows.empty()) {
    throw Error(SourceLocation{table.source},
                fmt::format("no rows with mechanism '{}' (the table has: {})", rows, join(table.mechanisms())));
  }
  const auto points = group_by_point(selected, convention);
  check_fit_budget(points, method, table.source);  // before any fit
  LoadedModel out;
  out.provenance = {table.source, table.sha256, rows, convention, robot.name, robot.geometry, MethodSelection::named, nullptr,
                    std::nullopt};
  FitMethod chosen = FitMethod::bilinear;
  if (method) {
    chosen = *method;
  } else {
    const CvReport report = cross_validate(points, robot.geometry, table.source);
    std::vector<std::pair<FitMethod, double>> scores;
    chosen = favoured_method(report, &scores);
    nlohmann::json by_method = nlohmann::json::object(), skipped = nlohmann::json::object();
    for (const auto& [name, score] : scores) by_method[std::string(core::enum_name(name))] = score;
    for (const auto& s : report.skipped) skipped[std::string(core::enum_name(s.method))] = s.reason;
    out.provenance.selected_by = MethodSelection::cross_validation;
    out.provenance.selection = {{"criterion", "smallest mean leave-one-out error over the points every method predicts"},
                                {"mean_error_um", by_method},
                                {"could_not_run", skipped}};
  }
  switch (chosen) {
    case FitMethod::bilinear: out.model = make_bilinear_model(fit_points(selected, convention), table.source); break;
    case FitMethod::symmetric: out.model = make_symmetric_model(points, table.source); break;
    case FitMethod::physical_0: out.model = fit_physical_model(points, robot.geometry, 0, table.source); break;
    case FitMethod::physical: out.model = fit_physical_model(points, robot.geometry, 1, table.source); break;
    case FitMethod::physical_2: out.model = fit_physical_model(points, robot.geometry, 2, table.source); break;
    case FitMethod::physical_spline: out.model = fit_physical_spline_model(points, robot.geometry, table.source); break;
  }
  out.label = fmt::format("{} fitted to {}{}", core::enum_name(chosen), table.source, rows.empty() ? "" : " rows " + rows);
  // A table whose displacements give a compliance that is not physical (negative, unbounded) is refused
  // here, where it enters, rather than reversing the correction where the model serves.
  if (const auto defect = find_model_defect(*out.model)) {
    throw Error(SourceLocation{table.source},
                fmt::format("{}; no model made: the {} model fitted to this table{} gives it (check the table's "
                            "signs and units)",
                            defect->describe(), core::enum_name(chosen), rows.empty() ? "" : " (rows " + rows + ")"));
  }
  return out;
}

void add_uncertainty(LoadedModel& loaded) {
  if (loaded.provenance.uncertainty) return;
  const Provenance& p = loaded.provenance;
  if (!p.geometry) throw Error(SourceLocation{loaded.label}, "the model records no robot geometry to refit with");
  const auto table = measurement::load_displacement_table(core::parse_data_ref(p.source)).filter(p.rows);
  // The method as fitted: a model file's "physical" with its order, as the method name fit_model uses.
  const std::optional<FitMethod> method = loaded.model->method();
  if (!method) {
    throw Error(SourceLocation{loaded.label}, fmt::format("{} is not a fitted model: no uncertainty to learn", loaded.model->description()));
  }
  loaded.provenance.uncertainty =
      estimate_method_uncertainty(*method, group_by_point(table, p.convention), *p.geometry, table.source);
}

bool is_builtin_model(const std::string& name) { return name.rfind("thesis-", 0) == 0; }

LoadedModel load_model(const std::string& name_or_path) {
  if (!is_builtin_model(name_or_path)) return load_model_file(core::parse_data_ref(name_or_path));
  // thesis-<oc|sc>[-<method>]: the preset's own table, rows and geometry.
  const std::string rest = name_or_path.substr(7);
  const std::string build = rest.substr(0, 2);
  const auto method = rest.size() > 3 && rest[2] == '-' ? core::find_enum<FitMethod>(rest.substr(3)) : FitMethod::bilinear;
  if ((build != "oc" && build != "sc") || (rest.size() > 2 && rest[2] != '-') || !method) {
    throw Error(fmt::format("unknown built-in model '{}' (use thesis-oc or thesis-sc, optionally with -<method>: {})",
                            name_or_path, core::enum_choices<FitMethod>()));
  }
  const kinematics::Robot robot = kinematics::load_robot(build + "-gu");
  LoadedModel out = fit_model(measurement::load_displacement_table(robot.compliance.table), robot.compliance.rows,
                              method, ForceConvention::measured, robot);
  out.label = name_or_path;
  return out;
}

measurement::DisplacementTable robot_table(const kinematics::Robot& robot) {
  if (robot.compliance.table.empty()) {
    throw Error(SourceLocation{robot.file.label()},
                fmt::format("robot '{}' names no displacement table (compliance.table)", robot.name));
  }
  const auto table = measurement::load_displacement_table(robot.compliance.table);
  auto rows = table.filter(robot.compliance.rows);
  if (rows.rows.empty()) {
    throw Error(SourceLocation{table.source}, fmt::format("no rows with mechanism '{}' for robot '{}' (the table has: {})",
                                                          robot.compliance.rows, robot.name, join(table.mechanisms())));
  }
  return rows;
}

GridBounds table_region(const measurement::DisplacementTable& table) {
  auto b = GridBounds::none();
  for (const auto& r : table.rows) b.include({r.x_m, r.y_m});
  return b;
}

void check_model_geometry(const LoadedModel& model, const kinematics::Robot& robot, bool force,
                          std::string_view how_to_force) {
  if (force) return;
  const Provenance& p = model.provenance;
  if (!p.geometry) {
    throw Error(fmt::format("model {} does not record the robot geometry it was fitted for (a file of format "
                            "version 1): refit it for robot '{}' or {}",
                            model.label, robot.name, how_to_force));
  }
  if (kinematics::geometry_hash(*p.geometry) != robot.geometry_hash()) {
    throw Error(fmt::format("model {} was fitted for robot '{}' (geometry {}), not for robot '{}' (geometry {}): fit "
                            "one for this robot or {}",
                            model.label, p.robot, short_hash(*p.geometry), robot.name, short_hash(robot.geometry),
                            how_to_force));
  }
}

LoadedModel load_robot_model(const kinematics::Robot& robot, const ModelRequest& request) {
  if (!request.model.empty()) {
    LoadedModel m = load_model(request.model);
    check_model_geometry(m, robot, request.force, request.how_to_force);
    return m;
  }
  const bool refit = request.refit || request.method.has_value();
  if (!refit && !robot.compliance.model.empty()) {
    LoadedModel m = load_model_file(robot.compliance.model);
    check_model_geometry(m, robot, request.force, request.how_to_force);
    return m;
  }
  if (robot.compliance.table.empty()) {
    throw Error(SourceLocation{robot.file.label()},
                fmt::format("robot '{}' has no compliance data: give compliance.table or compliance.model in its file, "
                            "or a model with --model",
                            robot.name));
  }
  const std::optional<FitMethod> method = refit ? request.method : robot.compliance.method;
  return fit_model(measurement::load_displacement_table(robot.compliance.table), robot.compliance.rows, method,
                   request.convention, robot);
}

}  // namespace stiffpath::compliance
