// Python: the digital twin (true compliance, servo + compliant-tip simulation) and the path metrics of a mark.
#include <pybind11/stl.h>

#include <fmt/format.h>

#include "arrays.hpp"
#include "parts.hpp"
#include "stiffpath/evaluation/path_metrics.hpp"
#include "stiffpath/simulation/run_metrics.hpp"
#include "stiffpath/simulation/simulator.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::python {

namespace {

simulation::SimulationResult simulate(const kinematics::Robot& robot, const py::array_t<JointRow, py::array::c_style>& joints,
                                      const std::optional<PyModel>& truth, double perturbation, std::uint64_t seed,
                                      double settle_s, double step_rate_hz, double servo_bandwidth_hz, double mark_rate_hz) {
  const JointRow* rows = joints.data();
  const auto n = static_cast<std::size_t>(joints.size());
  simulation::SimulationOptions options;
  options.settle_s = settle_s;
  options.plant.step_rate_hz = step_rate_hz;
  options.plant.servo_bandwidth_hz = servo_bandwidth_hz;
  options.mark_rate_hz = mark_rate_hz;
  py::gil_scoped_release unlocked;
  const std::shared_ptr<const compliance::Model> plant_truth =
      truth ? std::shared_ptr<const compliance::Model>(truth->model)
            : simulation::make_true_compliance(robot, {"", perturbation, seed});
  std::size_t i = 0;
  const simulation::JointSource source = [&]() -> std::optional<compensation::JointCommand> {
    if (i == n) return std::nullopt;
    const JointRow& r = rows[i++];
    compensation::JointCommand c;
    c.t_s = r.t_s;
    c.q_rad = Vec2(r.q_rad[0], r.q_rad[1]);
    c.qd_rad_s = Vec2(r.qd_rad_s[0], r.qd_rad_s[1]);
    c.qdd_rad_s2 = Vec2(r.qdd_rad_s2[0], r.qdd_rad_s2[1]);
    c.target_m = Vec2(r.target_m[0], r.target_m[1]);
    c.command_m = Vec2(r.command_m[0], r.command_m[1]);
    c.force_N = Vec2(r.force_N[0], r.force_N[1]);
    c.deflection_m = Vec2(r.deflection_m[0], r.deflection_m[1]);
    c.laser_on = r.laser;
    c.outside_grid = r.outside_grid;
    c.line = r.line;
    return c;
  };
  return simulation::simulate(source, robot, plant_truth, options);
}

std::vector<evaluation::Point2> to_points(const py::handle& points_m) {
  const auto a = pairs(points_m, "points_m");
  std::vector<evaluation::Point2> points(static_cast<std::size_t>(a.size() / 2));
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = {a.data()[2 * i], a.data()[2 * i + 1]};
  return points;
}

}  // namespace

void add_twin(py::module_& m) {
  m.def(
      "true_compliance",
      [](const kinematics::Robot& robot, double perturbation, std::uint64_t seed) {
        const auto truth = simulation::make_true_compliance(robot, {"", perturbation, seed});
        return PyModel{std::const_pointer_cast<compliance::Model>(truth), {}, "true compliance of " + robot.name};
      },
      py::arg("robot"), py::arg("perturbation") = 0.10, py::arg("seed") = 1,
      "The twin's true compliance field C_true (m/N): the physics-based model fitted to the robot's data, perturbed\n"
      "smoothly by ±perturbation (seeded), so that it differs from what the compensation model knows.");

  py::class_<simulation::SimulationResult>(m, "SimulationResult", "What the twin's laser marked, and its peaks (SI).")
      .def_property_readonly("marked_m", [](const simulation::SimulationResult& r) { return points_array(r.marked); },
                             "tool point while the laser was on (N, 2) in m")
      .def_property_readonly("commanded_m", [](const simulation::SimulationResult& r) { return points_array(r.commanded); },
                             "planned targets of the laser-on commands (N, 2) in m")
      .def_readonly("duration_s", &simulation::SimulationResult::duration_s)
      .def_readonly("peak_deflection_m", &simulation::SimulationResult::peak_deflection_m, "max |tip − base| during the job")
      .def_readonly("residual_vibration_m", &simulation::SimulationResult::residual_vibration_m, "max |tip − base| after it")
      .def_readonly("peak_tracking_error_m", &simulation::SimulationResult::peak_tracking_error_m, "servo error at the base point")
      .def_readonly("steps", &simulation::SimulationResult::steps);

  m.def("simulate", &simulate, py::arg("robot"), py::arg("joints"), py::kw_only(), py::arg("truth") = py::none(),
        py::arg("perturbation") = 0.10, py::arg("seed") = 1, py::arg("settle_s") = 0.10, py::arg("step_rate_hz") = 20000.0,
        py::arg("servo_bandwidth_hz") = 100.0, py::arg("mark_rate_hz") = 10000.0,
        "Runs joint commands (dtype stiffpath.joints_dtype, e.g. from Compensator.compensate) through the digital twin,\n"
        "as `stiffpath simulate`: servo-driven joints (bandwidth in Hz) and a compliant tip with the true compliance\n"
        "(truth, default true_compliance(robot, perturbation, seed)), integrated at step_rate_hz, holding the last\n"
        "command for settle_s s; the laser's mark is recorded at mark_rate_hz. Returns a SimulationResult.");

  py::class_<simulation::RunMetrics>(m, "RunMetrics", "The numbers the thesis read off its laser marks (§4.7), ISO 9283 (SI).")
      .def_readonly("length_m", &simulation::RunMetrics::length_m)
      .def_readonly("commanded_length_m", &simulation::RunMetrics::commanded_length_m)
      .def_readonly("length_error_m", &simulation::RunMetrics::length_error_m)
      .def_readonly("deviation_area_m2", &simulation::RunMetrics::deviation_area_m2)
      .def_readonly("max_deviation_m", &simulation::RunMetrics::max_deviation_m)
      .def_readonly("path_accuracy_m", &simulation::RunMetrics::path_accuracy_m, "ISO 9283 AT_p")
      .def_readonly("corners", &simulation::RunMetrics::corners)
      .def_readonly("cornering_round_off_m", &simulation::RunMetrics::cornering_round_off_m, "ISO 9283 CR")
      .def_readonly("cornering_overshoot_m", &simulation::RunMetrics::cornering_overshoot_m, "ISO 9283 CO")
      .def_readonly("residual_vibration_m", &simulation::RunMetrics::residual_vibration_m)
      .def_readonly("peak_deflection_m", &simulation::RunMetrics::peak_deflection_m);
  m.def("run_metrics", &simulation::measure_run, py::arg("result"), py::arg("sides") = 1,
        "Metrics of a simulated mark with `sides` straight sides (1: a line, 3: the triangle), as `stiffpath simulate`.");

  py::class_<evaluation::SideMetrics>(m, "SideMetrics", "One straight side of a marked path (SI).")
      .def_readonly("length_m", &evaluation::SideMetrics::length_m)
      .def_readonly("deviation_area_m2", &evaluation::SideMetrics::deviation_area_m2)
      .def_readonly("max_deviation_m", &evaluation::SideMetrics::max_deviation_m)
      .def_readonly("straightness_m", &evaluation::SideMetrics::straightness_m)
      .def_readonly("point_count", &evaluation::SideMetrics::point_count);
  py::class_<evaluation::PathMetrics>(m, "PathMetrics", "Length and deviation from straightness of a marked path (§4.7, SI).")
      .def_readonly("sides", &evaluation::PathMetrics::sides)
      .def_readonly("closed", &evaluation::PathMetrics::closed)
      .def_readonly("length_m", &evaluation::PathMetrics::length_m, "sum of the sides' lengths")
      .def_readonly("deviation_area_m2", &evaluation::PathMetrics::deviation_area_m2, "area between spline and line(s)")
      .def_readonly("max_deviation_m", &evaluation::PathMetrics::max_deviation_m)
      .def_readonly("straightness_m", &evaluation::PathMetrics::straightness_m, "largest peak to valley");
  m.def(
      "path_metrics",
      [](const py::handle& points_m, int sides) {
        const auto points = to_points(points_m);
        py::gil_scoped_release unlocked;
        return evaluation::measure_path(points, sides);
      },
      py::arg("points_m"), py::arg("sides") = 1,
      "Metrics of a marked path given as points (N, 2) in m, in order, with `sides` straight sides: length between\n"
      "start and end, area and maximum deviation between a smoothing spline and the fitted line(s) (thesis §4.7).");
}

}  // namespace stiffpath::python
