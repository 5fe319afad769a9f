// Python: displacement tables, compliance models (fit, load, save, C(x, y), predict), leave-one-out cross-validation.
#include <pybind11/eval.h>
#include <pybind11/stl.h>

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "arrays.hpp"
#include "parts.hpp"
#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::python {

PyModel to_py_model(compliance::LoadedModel loaded) {
  return {std::shared_ptr<compliance::Model>(std::move(loaded.model)), std::move(loaded.provenance),
          std::move(loaded.label)};
}

namespace {

using measurement::DisplacementTable;

// The fit method's name, or None for a model not fitted from a table.
py::object method_name(const compliance::Model& model) {
  const auto method = model.method();
  return method ? py::object(py::str(std::string(core::enum_name(*method)))) : py::object(py::none());
}

// The first point the model's `error` policy refuses raises stiffpath.Error naming it.
void check_inside(const PyModel& m, const double* p, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 point(p[2 * i], p[2 * i + 1]);
    if (m.model->refuses(point)) {
      const auto b = m.model->bounds();
      throw Error(fmt::format("p_m[{}] {} is outside model '{}''s measured rectangle x ∈ [{:.6g}, {:.6g}] mm, "
                              "y ∈ [{:.6g}, {:.6g}] mm (outside policy 'error'; set model.outside = 'clamp' or "
                              "'extrapolate' to use it)",
                              i, describe_point(point), m.label, b.x_min * 1e3, b.x_max * 1e3, b.y_min * 1e3,
                              b.y_max * 1e3));
    }
  }
}

py::array_t<double> model_compliance(const PyModel& m, const py::handle& x_m, const py::handle& y_m) {
  auto np = py::module_::import("numpy");
  const py::object stacked = np.attr("stack")(np.attr("broadcast_arrays")(x_m, y_m), -1);
  const auto points = pairs(stacked, "x_m, y_m");
  auto out = new_matrices(leading_shape(points));
  const auto n = static_cast<std::size_t>(points.size() / 2);
  check_inside(m, points.data(), n);
  double* c = out.mutable_data();
  for (std::size_t i = 0; i < n; ++i) {
    const Mat2 C = m.model->compliance(Vec2(points.data()[2 * i], points.data()[2 * i + 1]));
    c[4 * i + 0] = C(0, 0);
    c[4 * i + 1] = C(0, 1);
    c[4 * i + 2] = C(1, 0);
    c[4 * i + 3] = C(1, 1);
  }
  return out;
}

py::array_t<double> model_predict(const PyModel& m, const py::handle& p_m, const py::handle& F_N) {
  const auto [points, forces] = broadcast_pairs(p_m, "p_m", F_N, "F_N");
  auto out = new_pairs(leading_shape(points));
  const auto n = static_cast<std::size_t>(points.size() / 2);
  check_inside(m, points.data(), n);
  double* d = out.mutable_data();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 delta = m.model->predict(Vec2(points.data()[2 * i], points.data()[2 * i + 1]),
                                        Vec2(forces.data()[2 * i], forces.data()[2 * i + 1]));
    d[2 * i] = delta.x();
    d[2 * i + 1] = delta.y();
  }
  return out;
}

py::object to_python(const nlohmann::json& document) {
  return py::module_::import("json").attr("loads")(document.dump());
}

// The table's rows as a NumPy structured array (SI; NaN where a cell is missing).
py::object table_rows(const DisplacementTable& t) {
  py::list records;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& r : t.rows) {
    records.append(py::make_tuple(r.mechanism, measurement::to_string(r.direction), r.point, r.x_m, r.y_m, r.step,
                                  r.force_N, r.dx_m.value_or(nan), r.dy_m.value_or(nan), r.dz_m.value_or(nan),
                                  r.line));
  }
  auto np = py::module_::import("numpy");
  const py::list fields = py::eval(
      "[('mechanism', 'U8'), ('direction', 'U2'), ('point', 'U16'), ('x_m', 'f8'), ('y_m', 'f8'), ('step', 'i4'), "
      "('F_N', 'f8'), ('dx_m', 'f8'), ('dy_m', 'f8'), ('dz_m', 'f8'), ('line', 'i4')]");
  return np.attr("array")(records, py::arg("dtype") = fields);
}

// One column of table_from_arrays as Python values, broadcast to `n` rows (None: absent).
py::list column(const py::object& values, py::ssize_t n) {
  auto np = py::module_::import("numpy");
  const py::object flat = np.attr("ravel")(np.attr("broadcast_to")(np.attr("asarray")(values), py::make_tuple(n)));
  return flat.attr("tolist")();
}

// A number cell in mm (or N) of a value in m (or N); NaN or None: an empty cell (missing). Anything but a
// number (a string would be read in the file's units) raises stiffpath.Error naming the row and the array.
std::string number_cell(const py::handle& v, double factor, py::ssize_t row, const char* name) {
  if (v.is_none()) return {};
  if (!py::isinstance<py::float_>(v) && !py::isinstance<py::int_>(v)) {
    throw Error(fmt::format("{}[{}]: expected a number, got {}", name, row, py::repr(v).cast<std::string>()));
  }
  const double x = v.cast<double>();
  return std::isnan(x) ? std::string() : fmt::format("{:.17g}", x * factor);
}

// The arrays as the CSV text the table reader takes, so that they are checked exactly as a file is (line k + 2
// is row k).
DisplacementTable table_from_arrays(const py::object& point, const py::object& direction, const py::object& x_m,
                                    const py::object& y_m, const py::object& F_N, const py::object& dx_m,
                                    const py::object& dy_m, const py::object& mechanism, const py::object& step,
                                    const py::object& dz_m, const std::string& label) {
  auto np = py::module_::import("numpy");
  const auto n = static_cast<py::ssize_t>(py::len(np.attr("ravel")(np.attr("asarray")(point))));
  if (n == 0) throw Error(label + ": no rows (point is empty)");
  const py::list pt = column(point, n), dir = column(direction, n), x = column(x_m, n),
                 y = column(y_m, n), f = column(F_N, n), dx = column(dx_m, n),
                 dy = column(dy_m, n);
  const bool has_mech = !mechanism.is_none(), has_step = !step.is_none(), has_dz = !dz_m.is_none();
  const py::list mech = has_mech ? column(mechanism, n) : py::list();
  const py::list st = has_step ? column(step, n) : py::list();
  const py::list dz = has_dz ? column(dz_m, n) : py::list();
  std::string text = std::string(has_mech ? "mechanism," : "") + "direction,point,x_mm,y_mm," + (has_step ? "step," : "") +
                     "F_N,dx_mm,dy_mm" + (has_dz ? ",dz_mm" : "") + "\n";
  for (py::ssize_t i = 0; i < n; ++i) {
    if (has_mech) text += py::str(mech[i]).cast<std::string>() + ",";
    text += py::str(dir[i]).cast<std::string>() + "," + py::str(pt[i]).cast<std::string>() + ",";
    text += number_cell(x[i], 1e3, i, "x_m") + "," + number_cell(y[i], 1e3, i, "y_m") + ",";
    if (has_step) text += py::str(st[i]).cast<std::string>() + ",";
    text += number_cell(f[i], 1.0, i, "F_N") + "," + number_cell(dx[i], 1e3, i, "dx_m") + "," +
            number_cell(dy[i], 1e3, i, "dy_m");
    if (has_dz) text += "," + number_cell(dz[i], 1e3, i, "dz_m");
    text += "\n";
  }
  py::gil_scoped_release unlocked;
  return measurement::parse_displacement_table(text, label);
}

}  // namespace

void add_compliance(py::module_& m) {
  py::class_<DisplacementTable>(m, "DisplacementTable",
                                "Measured deflections of the platform point G under load (docs/measurement.md): one row\n"
                                "per (mechanism, load direction, point, load step). The thesis's tables 2.2–3.9 are built in.")
      .def_readonly("source", &DisplacementTable::source, "how errors name the table (a path or builtin:…)")
      .def_readonly("sha256", &DisplacementTable::sha256)
      .def("mechanisms", &DisplacementTable::mechanisms, "values of the mechanism column ('OC', 'SC')")
      .def("filter", &DisplacementTable::filter, py::arg("mechanism"), "the rows of one mechanism ('' keeps all)")
      .def("rows", &table_rows,
           "The rows as a NumPy structured array: mechanism, direction, point, x_m, y_m, step, F_N (relative to step 0),\n"
           "dx_m, dy_m, dz_m (NaN when missing), line (of the CSV file).")
      .def("__len__", [](const DisplacementTable& t) { return t.rows.size(); })
      .def("__repr__", [](const DisplacementTable& t) {
        return fmt::format("DisplacementTable('{}', {} rows)", t.source, t.rows.size());
      });

  m.def("load_table", py::overload_cast<const std::string&>(&measurement::load_displacement_table), py::arg("path"),
        "Loads a displacement table CSV ('builtin:thesis/displacements.csv' for the thesis's). Raises stiffpath.Error\n"
        "naming the file, line and column of a bad cell.");
  m.def("table_from_arrays", &table_from_arrays, py::arg("point"), py::arg("direction"), py::arg("x_m"), py::arg("y_m"),
        py::arg("F_N"), py::arg("dx_m"), py::arg("dy_m"), py::kw_only(), py::arg("mechanism") = py::none(),
        py::arg("step") = py::none(), py::arg("dz_m") = py::none(), py::arg("label") = "arrays",
        "A displacement table from arrays (one entry per row, broadcast): point ids, directions ('+x', '-x', '+y',\n"
        "'-y'), the nominal position x_m, y_m (m), the force F_N relative to step 0 (N), the deflections dx_m, dy_m\n"
        "(m; NaN: missing), and optionally mechanism ('OC', …), step (1, 2, …; else numbered per series) and dz_m.\n"
        "Checked exactly as a CSV file is: a bad value raises stiffpath.Error naming `label`, line k + 2 for row k,\n"
        "and the column.");
  m.def("thesis_table", [] { return measurement::load_displacement_table(measurement::thesis_dataset()); },
        "The thesis's displacement tables 2.2–3.9 (OC and SC rows), built in.");

  py::class_<PyModel>(m, "Model",
                      "A compliance model of the platform point: Δ = C(p)·F (thesis eqs. 4.6–4.7; the bilinear grid\n"
                      "model is eq. 4.12). Shared with the compensators built from it.")
      .def_property_readonly("method", [](const PyModel& p) { return method_name(*p.model); },
                             "'bilinear', 'symmetric', 'physical', 'physical-0', 'physical-2' or 'physical-spline'; None\n"
                             "for a model not fitted from a table (the twin's structural truth)")
      .def_readonly("label", &PyModel::label, "'thesis-oc', a file's path, or 'physical fitted to <table>'")
      .def_property_readonly("robot", [](const PyModel& p) { return p.provenance.robot; },
                             "name of the robot it was fitted for")
      .def_property_readonly("source", [](const PyModel& p) { return p.provenance.source; }, "the table it was fitted to")
      .def_property_readonly("bounds_m", [](const PyModel& p) {
        const auto b = p.model->bounds();
        return py::make_tuple(b.x_min, b.x_max, b.y_min, b.y_max);
      }, "measured rectangle (x_min, x_max, y_min, y_max) in m")
      .def_property("outside",
                    [](const PyModel& p) { return std::string(core::enum_name(p.model->outside_policy())); },
                    [](PyModel& p, const std::string& policy) {
                      p.model->set_outside_policy(core::parse_enum<compliance::OutsidePolicy>(policy));
                    },
                    "what the model does outside its rectangle: 'error' (refuse beyond 1 mm), 'clamp', 'extrapolate'")
      .def_property("zero_force",
                    [](const PyModel& p) { return std::string(core::enum_name(p.model->zero_force())); },
                    [](PyModel& p, const std::string& mode) { p.model->set_zero_force(core::parse_enum<compliance::ZeroForce>(mode)); },
                    "'relative' (Δ(p, F) − Δ(p, 0), default) or 'thesis_raw' (eq. 4.8's intercepts included)")
      .def("parameters", [](const PyModel& p) { return to_python(compliance::model_parameters(*p.model)); },
           "The fitted parameters (grid nodes or D(p) coefficients), as in model files.")
      .def("C", &model_compliance, py::arg("x_m"), py::arg("y_m"),
           "Compliance matrix C = ∂Δ/∂F (m/N) at points x_m, y_m (arrays broadcast together) → (..., 2, 2).")
      .def("predict", &model_predict, py::arg("p_m"), py::arg("F_N"),
           "Deflection Δ (m) of the point p_m (..., 2) in m under the force F_N (..., 2) in N (broadcast) → (..., 2).")
      .def("to_dict", [](const PyModel& p) { return to_python(compliance::model_to_json(*p.model, p.provenance)); },
           "The model-file document as a dict.")
      .def("save", [](const PyModel& p, const std::string& path) { compliance::save_model(path, *p.model, p.provenance); },
           py::arg("path"), "Writes the model file (JSON, atomically), readable by load_model and the CLI.")
      .def("__repr__", [](const PyModel& p) { return fmt::format("Model('{}', method='{}')", p.label, p.model->description()); });

  m.def("load_model", [](const std::string& name) { return to_py_model(compliance::load_model(name)); },
        py::arg("name_or_path"),
        "A built-in model ('thesis-oc', 'thesis-sc', 'thesis-oc-<method>') or a model file written by Model.save or\n"
        "`stiffpath fit -o`.");
  m.def("methods", &core::enum_name_list<compliance::FitMethod>, "Names of the fitting methods.");
  m.def(
      "fit",
      [](const DisplacementTable& table, const kinematics::Robot& robot, const std::string& method,
         const std::optional<std::string>& rows, const std::string& forces) {
        const auto convention = core::parse_enum<compliance::ForceConvention>(forces);
        const auto fit_method = compliance::parse_fit_method(method);
        py::gil_scoped_release unlocked;
        return to_py_model(compliance::fit_model(table, rows.value_or(robot.compliance.rows), fit_method, convention, robot));
      },
      py::arg("table"), py::arg("robot"), py::arg("method") = "auto", py::arg("rows") = py::none(),
      py::arg("forces") = "measured",
      "Fits a compliance model to a displacement table for a robot (thesis eqs. 4.8–4.12 for 'bilinear').\n\n"
      "method: one of methods(), or 'auto' for the one leave-one-out cross-validation favours.\n"
      "rows: the table's mechanism rows ('OC', 'SC'); default the robot's own.\n"
      "forces: 'measured' (the table's F_N, relative to step 0) or 'nominal' (its F_nominal_N column: the\n"
      "round loads the campaign names; a table without that column is refused).");
  m.def(
      "robot_model",
      [](const kinematics::Robot& robot, const std::string& method) {
        compliance::ModelRequest request;
        if (!method.empty()) {
          request.refit = true;
          request.method = compliance::parse_fit_method(method);
        }
        py::gil_scoped_release unlocked;
        return to_py_model(compliance::load_robot_model(robot, request));
      },
      py::arg("robot"), py::arg("method") = "",
      "The robot's own compliance model: its model file, or its table fitted with `method` (default: the robot\n"
      "file's method, else the one cross-validation favours) — what the CLI's run uses.");

  py::class_<compliance::CvPoint>(m, "CvPoint", "One held-out point of the cross-validation.")
      .def_readonly("id", &compliance::CvPoint::id)
      .def_readonly("predicted", &compliance::CvPoint::predicted, "False where the method cannot predict it")
      .def_readonly("interior", &compliance::CvPoint::interior)
      .def_readonly("mean_abs_error_um", &compliance::CvPoint::mean_abs_error_um, "mean |Δ component error| (µm)")
      .def_readonly("mean_vector_error_um", &compliance::CvPoint::mean_vector_error_um, "mean |Δ error| (µm)");
  py::class_<compliance::CvMethod>(m, "CvMethod", "Leave-one-out result of one method.")
      .def_property_readonly("method", [](const compliance::CvMethod& c) { return std::string(core::enum_name(c.method)); })
      .def_readonly("description", &compliance::CvMethod::description)
      .def_readonly("points", &compliance::CvMethod::points)
      .def_readonly("predicted", &compliance::CvMethod::predicted, "number of points it could predict")
      .def_readonly("mean_um", &compliance::CvMethod::mean_um, "mean error over those points (µm)")
      .def_readonly("max_um", &compliance::CvMethod::max_um, "largest error (µm)")
      .def_readonly("interior_mean_um", &compliance::CvMethod::interior_mean_um, "mean over the interior points (µm)")
      .def("__repr__", [](const compliance::CvMethod& c) {
        return fmt::format("CvMethod('{}', mean {:.1f} µm over {} points)", core::enum_name(c.method), c.mean_um, c.predicted);
      });
  py::class_<compliance::CvReport>(m, "CvReport", "Leave-one-out cross-validation of every method on a table.")
      .def_readonly("source", &compliance::CvReport::source)
      .def_readonly("rows", &compliance::CvReport::rows)
      .def_readonly("robot", &compliance::CvReport::robot)
      .def_readonly("methods", &compliance::CvReport::methods)
      .def_property_readonly("skipped", [](const compliance::CvReport& r) {
        py::dict out;
        for (const auto& s : r.skipped) out[py::str(std::string(core::enum_name(s.method)))] = s.reason;
        return out;
      }, "{method: why it could not run}")
      .def_property_readonly("favoured", [](const compliance::CvReport& r) { return std::string(core::enum_name(compliance::favoured_method(r))); },
                             "the method with the smallest mean error over the points all methods predict");
  m.def(
      "cv",
      [](const DisplacementTable& table, const kinematics::Robot& robot, const std::optional<std::string>& rows,
         const std::string& forces, const std::string& zero_force) {
        const auto convention = core::parse_enum<compliance::ForceConvention>(forces);
        const auto zero = core::parse_enum<compliance::ZeroForce>(zero_force);
        const std::string name = rows.value_or(robot.compliance.rows);
        const auto selected = table.filter(name);
        if (selected.rows.empty()) throw Error(SourceLocation{table.source}, "no rows with mechanism '" + name + "'");
        py::gil_scoped_release unlocked;
        auto report = compliance::cross_validate(compliance::group_by_point(selected, convention), robot.geometry,
                                                 table.source, zero);
        report.rows = name;
        report.robot = robot.name;
        report.convention = convention;
        return report;
      },
      py::arg("table"), py::arg("robot"), py::arg("rows") = py::none(), py::arg("forces") = "measured",
      py::arg("zero_force") = "relative",
      "Leave-one-out cross-validation of every method on the table's rows (as `stiffpath cv`): per method the\n"
      "error at each held-out point at the highest load step (µm).");
}

}  // namespace stiffpath::python
