// MEX commands on kinematics and compliance: ik, fk, fit, predict, compliance, cv (as the CLI's kin, fit, predict, cv).
#include <fmt/format.h>

#include <cmath>

#include "mex_args.hpp"
#include "mex_commands.hpp"
#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/compliance/uncertainty.hpp"
#include "stiffpath/core/data_ref.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::mex {

namespace {

// A table argument: '' the robot's own, 'thesis' the thesis's data, else a CSV file (or builtin: reference).
core::DataRef table_of(const std::string& text, const kinematics::Robot& robot) {
  if (text.empty()) {
    if (robot.compliance.table.empty()) {
      throw Error(fmt::format("robot '{}' names no displacement table: give options.table", robot.name));
    }
    return robot.compliance.table;
  }
  return text == "thesis" ? measurement::thesis_dataset() : core::parse_data_ref(text);
}

std::vector<Vec2> rows_of(const Matrix& m) {
  std::vector<Vec2> out(m.rows);
  for (std::size_t i = 0; i < m.rows; ++i) out[i] = Vec2(m(i, 0), m(i, 1));
  return out;
}

// The model argument with predict's options: a model file or built-in name ('' with options.robot: the robot's own).
compliance::LoadedModel model_of(const std::string& name, Options& o) {
  const auto robot = o.text("robot");
  const bool force = o.flag("force_model").value_or(false);
  compliance::LoadedModel loaded;
  if (robot) {
    compliance::ModelRequest request;
    request.model = name;
    request.force = force;
    request.how_to_force = "set options.force_model = true";
    loaded = compliance::load_robot_model(kinematics::load_robot(*robot), request);
  } else {
    if (name.empty()) throw UsageError("model '' (the robot's own) needs options.robot");
    loaded = compliance::load_model(name);
  }
  if (const auto outside = o.text("outside")) {
    loaded.model->set_outside_policy(core::parse_enum<compliance::OutsidePolicy>(*outside));
  }
  return loaded;
}

void refuse_outside(const compliance::LoadedModel& loaded, const Vec2& p, std::size_t row) {
  if (!loaded.model->refuses(p)) return;
  const auto b = loaded.model->bounds();
  throw Error(fmt::format("p_m row {} ({}, {}) mm is more than {:g} mm outside the measured region of model {}, x [{:.3f}, "
                          "{:.3f}] mm, y [{:.3f}, {:.3f}] mm (set options.outside = 'clamp' or 'extrapolate')",
                          row + 1, p.x() * 1e3, p.y() * 1e3, compliance::kOutsideMargin_m * 1e3, loaded.label,
                          b.x_min * 1e3, b.x_max * 1e3, b.y_min * 1e3, b.y_max * 1e3));
}

}  // namespace

void ik(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 3, 3, "q_rad = stiffpath('ik', robot, p_m)  % p_m: N×2 in m");
  const auto robot = robot_arg(prhs[1]);
  const auto p = rows_of(matrix_arg(prhs[2], "p_m", 2, 2));
  std::vector<Vec2> q(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    try {
      q[i] = robot.inverse(p[i]);
    } catch (const Error& e) {
      throw Error(fmt::format("p_m row {}: {}", i + 1, e.message()));
    }
  }
  plhs[0] = pairs(q);
}

void fk(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 3, 3, "p_m = stiffpath('fk', robot, q_rad)  % q_rad: N×2 in rad");
  const auto robot = robot_arg(prhs[1]);
  const auto q = rows_of(matrix_arg(prhs[2], "q_rad", 2, 2));
  std::vector<Vec2> p(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    try {
      p[i] = robot.forward(q[i]);  // finite, within the joints' ranges (as `kin fk`)
    } catch (const Error& e) {
      throw Error(fmt::format("q_rad row {}: {}", i + 1, e.message()));
    }
  }
  plhs[0] = pairs(p);
}

// model = stiffpath('fit', robot [, options]): the model document `stiffpath fit --json` prints, as a struct.
void fit(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 2, 5, "model = stiffpath('fit', robot [, options])  % options: table, method, rows, forces, outside, "
                   "zero_force, output");
  const auto robot = robot_arg(prhs[1]);
  std::string table_text, method = "auto", output, rows = robot.compliance.rows, forces = "measured";
  std::string outside = "error", zero_force = "relative";
  if (nrhs == 5) {  // the positional form of earlier versions: robot, table, method, model file
    table_text = text_arg(prhs[2], "table_csv");
    method = text_arg(prhs[3], "method");
    output = text_arg(prhs[4], "model_file");
  } else {
    if (nrhs == 4) throw UsageError("usage: model = stiffpath('fit', robot [, options])");
    Options o(nrhs == 3 ? prhs[2] : nullptr);
    table_text = o.text("table").value_or("");
    method = o.text("method").value_or(method);
    rows = o.text("rows").value_or(rows);
    forces = o.text("forces").value_or(forces);
    outside = o.text("outside").value_or(outside);
    zero_force = o.text("zero_force").value_or(zero_force);
    output = o.text("output").value_or("");
    o.finish();
  }
  if (nrhs == 5 && !table_text.empty()) rows = robot.compliance.rows;
  const auto table = measurement::load_displacement_table(table_of(table_text, robot));
  auto fitted = compliance::fit_model(table, rows, compliance::parse_fit_method(method),
                                      core::parse_enum<compliance::ForceConvention>(forces), robot);
  fitted.model->set_outside_policy(core::parse_enum<compliance::OutsidePolicy>(outside));
  fitted.model->set_zero_force(core::parse_enum<compliance::ZeroForce>(zero_force));
  try {
    compliance::add_uncertainty(fitted);  // as `stiffpath fit`: the file carries its predictions' band when it can
  } catch (const Error&) {
  }
  if (!output.empty()) compliance::save_model(output, *fitted.model, fitted.provenance);
  plhs[0] = from_json(compliance::model_to_json(*fitted.model, fitted.provenance));
}

// r = stiffpath('predict', model, p_m, F_N [, options]): deflections, compliance and their 95 % bands.
void predict(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 4, 5, "r = stiffpath('predict', model, p_m, F_N [, options])  % options: robot, outside, force_model");
  Options o(nrhs == 5 ? prhs[4] : nullptr);
  auto loaded = model_of(text_arg(prhs[1], "model"), o);
  o.finish();
  const auto p = rows_of(matrix_arg(prhs[2], "p_m", 2, 2));
  const auto F = rows_of(matrix_arg(prhs[3], "F_N", 2, 2));
  if (F.size() != p.size() && F.size() != 1) throw UsageError("F_N must have one row or as many rows as p_m");
  std::string no_band;
  try {
    compliance::add_uncertainty(loaded);
  } catch (const Error& e) {
    no_band = e.message();
  }
  const auto& u = loaded.provenance.uncertainty;
  const std::size_t n = p.size();
  std::vector<Vec2> d(n), sigma(n), band(n), measured_band(n);
  std::vector<bool> inside(n);
  const mwSize dims[3] = {2, 2, static_cast<mwSize>(n)};
  mxArray* C = mxCreateNumericArray(3, dims, mxDOUBLE_CLASS, mxREAL);
  double* c = mxGetPr(C);
  for (std::size_t i = 0; i < n; ++i) {
    refuse_outside(loaded, p[i], i);
    const Vec2 force = F[F.size() == 1 ? 0 : i];
    d[i] = loaded.model->predict(p[i], force);
    inside[i] = loaded.model->inside(p[i]);
    const auto Ci = loaded.model->compliance(p[i]);
    c[4 * i + 0] = Ci(0, 0);
    c[4 * i + 1] = Ci(1, 0);
    c[4 * i + 2] = Ci(0, 1);
    c[4 * i + 3] = Ci(1, 1);
    if (u) {
      const auto cov = u->deflection_covariance(p[i], force), meas = u->measurement_covariance(p[i], force);
      const double k = u->band_factor();
      sigma[i] = Vec2(std::sqrt(cov(0, 0)), std::sqrt(cov(1, 1)));
      band[i] = k * sigma[i];
      measured_band[i] = Vec2(k * std::sqrt(meas(0, 0)), k * std::sqrt(meas(1, 1)));
    }
  }
  StructBuilder s;
  s.add("model", loaded.label).add("method", loaded.model->description()).add("d_m", pairs(d)).add("C_m_per_N", C);
  s.add("inside", logical_column(inside));
  if (u) {
    s.add("d_sigma_m", pairs(sigma)).add("d_band_95_m", pairs(band)).add("measured_d_band_95_m", pairs(measured_band));
    s.add("uncertainty_basis", compliance::to_string(u->basis));
  } else {
    s.add("uncertainty", "unknown: " + no_band);
  }
  plhs[0] = s.build();
}

// C = stiffpath('compliance', model, p_m [, options]): 2×2×N compliance matrices (m/N).
void compliance_matrices(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 3, 4, "C = stiffpath('compliance', model, p_m [, options])  % 2×2×N in m/N");
  Options o(nrhs == 4 ? prhs[3] : nullptr);
  const auto loaded = model_of(text_arg(prhs[1], "model"), o);
  o.finish();
  const auto p = rows_of(matrix_arg(prhs[2], "p_m", 2, 2));
  const mwSize dims[3] = {2, 2, static_cast<mwSize>(p.size())};
  plhs[0] = mxCreateNumericArray(3, dims, mxDOUBLE_CLASS, mxREAL);
  double* c = mxGetPr(plhs[0]);
  for (std::size_t i = 0; i < p.size(); ++i) {
    refuse_outside(loaded, p[i], i);
    const auto C = loaded.model->compliance(p[i]);
    c[4 * i + 0] = C(0, 0);
    c[4 * i + 1] = C(1, 0);
    c[4 * i + 2] = C(0, 1);
    c[4 * i + 3] = C(1, 1);
  }
}

// cv = stiffpath('cv', robot [, options]): leave-one-out cross-validation of every method, as `stiffpath cv --json`.
void cv(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 2, 3, "cv = stiffpath('cv', robot [, options])  % options: table, rows, forces, zero_force");
  const auto robot = robot_arg(prhs[1]);
  Options o(nrhs == 3 ? prhs[2] : nullptr);
  const auto table = measurement::load_displacement_table(table_of(o.text("table").value_or(""), robot));
  const std::string rows_name = o.text("rows").value_or(robot.compliance.rows);
  const auto convention = core::parse_enum<compliance::ForceConvention>(o.text("forces").value_or("measured"));
  const auto zero_force = core::parse_enum<compliance::ZeroForce>(o.text("zero_force").value_or("relative"));
  o.finish();
  const auto rows = table.filter(rows_name);
  if (rows.rows.empty()) throw Error(SourceLocation{table.source}, "no rows with mechanism '" + rows_name + "'");
  auto report = compliance::cross_validate(compliance::group_by_point(rows, convention), robot.geometry, table.source,
                                           zero_force, true);
  std::vector<std::pair<compliance::FitMethod, double>> scores;
  const compliance::FitMethod favoured = compliance::favoured_method(report, &scores);
  nlohmann::json methods = nlohmann::json::object();
  for (std::size_t k = 0; k < report.methods.size(); ++k) {
    const auto& m = report.methods[k];
    nlohmann::json points = nlohmann::json::array();
    for (const auto& p : m.points) {
      points.push_back({{"point", p.id}, {"x_m", p.position.x()}, {"y_m", p.position.y()}, {"predicted", p.predicted},
                        {"interior", p.interior},
                        {"error_m", p.predicted ? nlohmann::json(p.mean_abs_error_um * 1e-6) : nlohmann::json(nullptr)},
                        {"vector_error_m", p.predicted ? nlohmann::json(p.mean_vector_error_um * 1e-6) : nlohmann::json(nullptr)}});
    }
    methods[std::string(core::enum_name(m.method))] = {
        {"description", m.description},
        {"predicted_points", m.predicted},
        {"mean_error_m", m.mean_um * 1e-6},
        {"max_error_m", m.max_um * 1e-6},
        {"interior_mean_error_m", m.interior_mean_um * 1e-6},
        {"common_points_mean_error_m", scores[k].second * 1e-6},
        {"band_95", {{"cells", m.band_cells},
                     {"inside", m.inside_band},
                     {"mean_half_width_m", m.mean_band_um * 1e-6},
                     {"fraction", m.band_cells > 0 ? static_cast<double>(m.inside_band) / m.band_cells : 0.0}}},
        {"points", points}};
  }
  nlohmann::json skipped = nlohmann::json::object();
  for (const auto& s : report.skipped) skipped[std::string(core::enum_name(s.method))] = s.reason;
  plhs[0] = from_json({{"source", report.source},
                       {"rows", rows_name},
                       {"robot", robot.name},
                       {"force_convention", core::enum_name(convention)},
                       {"zero_force", core::enum_name(zero_force)},
                       {"favoured_method", core::enum_name(favoured)},
                       {"methods", methods},
                       {"could_not_run", skipped}});
}

}  // namespace stiffpath::mex
