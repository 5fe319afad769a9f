// Python: stiffpath.run — the main job (G-code → compensated joint commands) as `stiffpath run` does it, via job::JobSpec.
#include <pybind11/stl.h>

#include <fmt/format.h>

#include "arrays.hpp"
#include "parts.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/job/prepared_job.hpp"

namespace stiffpath::python {

namespace {

template <core::NamedEnum E>
E parsed(const char* argument, const std::string& text) {
  try {
    return core::parse_enum<E>(text);
  } catch (const Error& e) {
    throw py::value_error(fmt::format("{}: {}", argument, e.message()));
  }
}

// The robot argument: a Robot, or a preset name or robot file.
kinematics::Robot robot_of(const py::handle& robot) {
  if (py::isinstance<py::str>(robot)) return kinematics::load_robot(robot.cast<std::string>());
  return robot.cast<kinematics::Robot>();
}

py::dict summary_dict(const job::PreparedJob& job, const job::JobSummary& s) {
  const job::JobSpec& spec = job.spec;
  py::dict d;
  d["job"] = job.program.label();
  d["robot"] = spec.robot.name;
  d["model"] = job.model_label;
  d["compensation"] = spec.compensate;
  d["method"] = spec.compensate ? std::string(core::enum_name(spec.method)) : std::string("none");
  d["gain"] = spec.compensate ? spec.gain : 0.0;
  d["damping_ratio"] = *spec.damping_ratio;
  d["smooth_s"] = *spec.smooth_s;
  d["shaper"] = std::string(core::enum_name(spec.shaper));
  d["filters"] = job.filters_text();
  d["jerk_m_s3"] = spec.plan.limits.max_jerk_m_s3;
  d["lowest_frequency_hz"] = job.lowest_frequency_hz > 0.0 ? py::object(py::float_(job.lowest_frequency_hz)) : py::object(py::none());
  d["duration_s"] = s.duration_s;
  d["samples"] = s.samples;
  d["rate_hz"] = spec.plan.rate_hz;
  d["peak_deflection_m"] = s.peak_deflection_m;
  d["peak_correction_m"] = s.peak_correction_m;
  d["peak_force_N"] = s.peak_force_N;
  d["samples_outside_grid"] = s.samples_outside_grid;
  return d;
}

py::tuple run(const std::optional<std::string>& file, const std::optional<std::string>& gcode, const py::object& robot,
              const py::object& model, bool thesis, bool compensate, const std::optional<std::string>& method,
              std::optional<double> gain, std::optional<double> damping_ratio, std::optional<double> smooth_s,
              const std::optional<std::string>& shaper, const std::optional<std::string>& outside,
              const std::optional<std::string>& acceleration, std::optional<double> max_acceleration_m_s2,
              const py::object& max_jerk_m_s3, std::optional<double> max_velocity_m_s, std::optional<double> rate_hz,
              const std::optional<std::pair<double, double>>& work_offset_m,
              const std::optional<std::pair<double, double>>& start_m, bool force_model) {
  if (file.has_value() == gcode.has_value()) throw py::value_error("run: give exactly one of file= or gcode= (text)");
  const kinematics::Robot r = robot_of(robot);
  job::JobSpec spec = thesis ? job::thesis_job(r) : job::default_job(r);
  if (!model.is_none()) {
    if (thesis) throw py::value_error("run: thesis=True names its own model; give no model=");
    if (py::isinstance<py::str>(model)) {
      spec.model.request.model = model.cast<std::string>();
      spec.model.request.force = force_model;
      spec.model.request.how_to_force = "pass force_model=True";
    } else {
      const PyModel& m = model.cast<const PyModel&>();
      compliance::check_model_geometry({nullptr, m.provenance, m.label}, r, force_model, "pass force_model=True");
      spec.model.given = m.model;
      spec.model.given_label = m.label;
    }
  }
  spec.compensate = compensate;
  if (method) spec.method = parsed<compensation::Method>("method", *method);
  if (gain) spec.gain = *gain;
  if (damping_ratio) spec.damping_ratio = *damping_ratio;
  if (smooth_s) spec.smooth_s = *smooth_s;
  if (shaper) spec.shaper = parsed<compensation::FilterKind>("shaper", *shaper);
  if (outside) spec.outside = parsed<compliance::OutsidePolicy>("outside", *outside);
  if (acceleration) spec.acceleration = parsed<job::AccelerationSource>("acceleration", *acceleration);
  auto& limits = spec.plan.limits;
  if (max_velocity_m_s) limits.max_velocity_m_s = *max_velocity_m_s;
  if (max_acceleration_m_s2) limits.max_acceleration_m_s2 = *max_acceleration_m_s2;
  limits.max_jerk_m_s3 = motion::default_jerk_m_s3(limits.max_acceleration_m_s2);
  if (py::isinstance<py::str>(max_jerk_m_s3)) {
    if (max_jerk_m_s3.cast<std::string>() != "auto") throw py::value_error("max_jerk_m_s3: a number (m/s³) or 'auto'");
    spec.jerk = job::JerkRule::tip_frequency;
  } else if (!max_jerk_m_s3.is_none()) {
    limits.max_jerk_m_s3 = max_jerk_m_s3.cast<double>();
  }
  if (rate_hz) spec.plan.rate_hz = *rate_hz;
  if (work_offset_m) spec.plan.gcode.work_offset_m = Vec2(work_offset_m->first, work_offset_m->second);
  if (start_m) spec.plan.gcode.start_position_m = Vec2(start_m->first, start_m->second);
  spec.plan.gcode.home_position_m = r.home_m;
  RowWriter writer;
  std::optional<job::PreparedJob> prepared;
  job::JobSummary summary;
  {
    py::gil_scoped_release unlocked;
    prepared = job::prepare(std::move(spec), file ? job::Program::file(*file) : job::Program::text(*gcode, "<gcode>"));
    job::check_output(*prepared, "-");  // the arrays are kept in memory: the cap of a written job holds
    summary = job::run(*prepared, &writer);
  }
  return py::make_tuple(writer.array(), summary_dict(*prepared, summary));
}

}  // namespace

void add_job(py::module_& m) {
  m.def("run", &run, py::kw_only(), py::arg("file") = py::none(), py::arg("gcode") = py::none(),
        py::arg("robot") = "oc-gu", py::arg("model") = py::none(), py::arg("thesis") = false,
        py::arg("compensate") = true, py::arg("method") = py::none(), py::arg("gain") = py::none(),
        py::arg("damping_ratio") = py::none(), py::arg("smooth_s") = py::none(), py::arg("shaper") = py::none(),
        py::arg("outside") = py::none(), py::arg("acceleration") = py::none(),
        py::arg("max_acceleration_m_s2") = py::none(), py::arg("max_jerk_m_s3") = py::none(),
        py::arg("max_velocity_m_s") = py::none(), py::arg("rate_hz") = py::none(), py::arg("work_offset_m") = py::none(),
        py::arg("start_m") = py::none(), py::arg("force_model") = false,
        "The main job, exactly as `stiffpath run` does it: plans a G-code program (file= or gcode= text), compensates\n"
        "every sample and returns (joints, summary): joints of dtype stiffpath.joints_dtype, summary a dict like\n"
        "`run --json`'s. Every option left None keeps the defaults every surface shares (docs/compensation.md):\n"
        "robot: a Robot or a preset/robot file; model: a Model, a model file or built-in name (default: the robot's\n"
        "own); thesis=True: the thesis's method (bilinear model, quasi-static, no filter); compensate=False: the\n"
        "planned path converted to joints as it is; method 'dynamic' | 'quasi-static'; gain; damping_ratio;\n"
        "smooth_s (s; default 0.008 when compensating, 0 without); shaper 'none' | 'zv' | 'zvd'; outside 'error' |\n"
        "'clamp' | 'extrapolate'; acceleration 'analytic' | 'numeric'; max_acceleration_m_s2 (default 5 g);\n"
        "max_jerk_m_s3 (default acceleration / 5 ms; 'auto': acceleration × the tip's lowest frequency);\n"
        "max_velocity_m_s; rate_hz (default 2000); work_offset_m, start_m: (x, y) in m; force_model=True accepts a\n"
        "model fitted for another robot geometry. The first refused sample\n"
        "raises stiffpath.Error naming the G-code line, the time and the limit.");
}

}  // namespace stiffpath::python
