// Python: the digital twin (true compliance, servo + compliant-tip simulation) and the path metrics of a mark.
#include <pybind11/stl.h>

#include <fmt/format.h>

#include "arrays.hpp"
#include "parts.hpp"
#include "stiffpath/evaluation/path_metrics.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/simulation/cg_lever.hpp"
#include "stiffpath/simulation/run_metrics.hpp"
#include "stiffpath/simulation/simulator.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::python {

namespace {

// A simulated job as Python keeps it: the whole mark (stroke by stroke, concatenated), and the metrics that
// `stiffpath simulate` prints, measured per stroke while the twin ran.
struct PySimulation {
  simulation::SimulationResult result;
  std::vector<std::size_t> stroke_starts;  // index of each stroke's first marked point
  std::vector<simulation::StrokeMetrics> stroke_metrics;
  std::optional<simulation::RunMetrics> metrics;
  std::string refusal;  // why there are no metrics (the laser marked too little)
};

// What `stiffpath simulate` does with its flags (twin_flags): C_true of the family, the loaded or ideal servo, the
// CG lever unless turned off; then the job through the twin, each stroke measured as it ends.
PySimulation simulate(const kinematics::Robot& robot, const py::handle& joints_in,
                      const std::optional<PyModel>& truth, const std::string& truth_family, double perturbation,
                      std::uint64_t seed, const std::string& servo, bool cg_lever, int sides, double mass_scale,
                      std::optional<double> damping_ratio, double motor_inertia_kg_m2, double load_feedforward,
                      const std::string& load_feedforward_from, double settle_s, double step_rate_hz,
                      double servo_bandwidth_hz, double mark_rate_hz) {
  if (servo != "loaded" && servo != "ideal") throw Error(fmt::format("simulate: servo must be 'loaded' or 'ideal', got '{}'", servo));
  if (load_feedforward_from != "reference" && load_feedforward_from != "command") {
    throw Error(fmt::format("simulate: load_feedforward_from must be 'reference' or 'command', got '{}'", load_feedforward_from));
  }
  if (sides < 0) throw Error(fmt::format("simulate: sides must be >= 0 (0: inferred per stroke), got {}", sides));
  const auto joints = joint_records(joints_in, "joints");
  const JointRow* rows = joints.data();
  const auto n = static_cast<std::size_t>(joints.size());
  simulation::SimulationOptions options;
  options.settle_s = settle_s;
  options.mark_rate_hz = mark_rate_hz;
  options.mass_scale = mass_scale;
  options.plant.step_rate_hz = step_rate_hz;
  options.plant.servo_bandwidth_hz = servo_bandwidth_hz;
  options.plant.tip_damping_ratio = damping_ratio;
  options.plant.motor_inertia_kg_m2 = motor_inertia_kg_m2;
  options.plant.load_feedforward = load_feedforward;
  options.plant.load_feedforward_from_command = load_feedforward_from == "command";
  options.plant.servo_feels_load = servo == "loaded";
  simulation::TrueComplianceOptions truth_options;
  truth_options.family = core::parse_enum<simulation::TrueFamily>(truth_family);
  truth_options.perturbation = perturbation;
  truth_options.seed = seed;
  PySimulation out;
  py::gil_scoped_release unlocked;
  if (cg_lever) options.cg_lever = simulation::make_cg_lever(robot);
  const std::shared_ptr<const compliance::Model> plant_truth =
      truth ? std::shared_ptr<const compliance::Model>(truth->model) : simulation::make_true_compliance(robot, truth_options);
  simulation::RunMeter meter(sides);
  std::size_t i = 0;
  const simulation::JointSource source = [&]() -> std::optional<compensation::JointCommand> {
    if (i == n) return std::nullopt;
    return to_command(rows[i++]);
  };
  std::vector<Vec2> marked, commanded;
  std::vector<std::size_t> first_mark;
  out.result = simulation::simulate(source, robot, plant_truth, options, [&](const simulation::Stroke& stroke) {
    meter.add(stroke);
    out.stroke_starts.push_back(marked.size());
    for (const auto k : stroke.first_mark) first_mark.push_back(marked.size() + k);
    marked.insert(marked.end(), stroke.marked.begin(), stroke.marked.end());
    commanded.insert(commanded.end(), stroke.commanded.begin(), stroke.commanded.end());
  });
  out.result.marked = std::move(marked);
  out.result.commanded = std::move(commanded);
  out.result.first_mark = std::move(first_mark);
  out.stroke_metrics = meter.strokes();
  try {
    out.metrics = meter.totals(out.result);
  } catch (const Error& e) {
    out.refusal = e.what();
  }
  return out;
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
      [](const kinematics::Robot& robot, double perturbation, std::uint64_t seed, const std::string& family) {
        simulation::TrueComplianceOptions options;
        options.perturbation = perturbation;
        options.seed = seed;
        options.family = core::parse_enum<simulation::TrueFamily>(family);
        const auto truth = simulation::make_true_compliance(robot, options);
        return PyModel{std::const_pointer_cast<compliance::Model>(truth), {}, "true compliance of " + robot.name};
      },
      py::arg("robot"), py::arg("perturbation") = 0.10, py::arg("seed") = 1, py::arg("family") = "structural",
      "The twin's true compliance field C_true (m/N): a model of `family` ('structural': virtual joints, a family no\n"
      "compensation model has; 'physical': C = U⁻ᵀ D U⁻¹) fitted to the robot's data, perturbed smoothly by\n"
      "±perturbation (seeded), so that it differs from what the compensation model knows.");

  py::class_<PySimulation>(m, "Simulation", "What the twin's laser marked, its peaks and the mark's metrics (SI).")
      .def_property_readonly("marked_m", [](const PySimulation& r) { return points_array(r.result.marked); },
                             "tool point while the laser was on (N, 2) in m, the strokes one after the other")
      .def_property_readonly("commanded_m", [](const PySimulation& r) { return points_array(r.result.commanded); },
                             "planned targets of the laser-on commands (M, 2) in m")
      .def_property_readonly("stroke_starts", [](const PySimulation& r) { return r.stroke_starts; },
                             "index into marked_m of each laser stroke's first point")
      .def_property_readonly("duration_s", [](const PySimulation& r) { return r.result.duration_s; }, "commanded job time")
      .def_property_readonly("peak_deflection_m", [](const PySimulation& r) { return r.result.peak_deflection_m; },
                             "max |tip − base| during the job")
      .def_property_readonly("residual_vibration_m", [](const PySimulation& r) { return r.result.residual_vibration_m; },
                             "max |tip − base| after it")
      .def_property_readonly("peak_tracking_error_m", [](const PySimulation& r) { return r.result.peak_tracking_error_m; },
                             "servo error at the base point")
      .def_property_readonly("steps", [](const PySimulation& r) { return r.result.steps; }, "integration steps")
      .def_property_readonly("strokes", [](const PySimulation& r) { return r.result.strokes; }, "laser strokes")
      .def_property_readonly("stroke_metrics", [](const PySimulation& r) { return r.stroke_metrics; },
                             "StrokeMetrics of each stroke, as `stiffpath simulate --json` lists them")
      .def_property_readonly(
          "metrics",
          [](const PySimulation& r) {
            if (!r.metrics) throw Error(r.refusal);
            return *r.metrics;
          },
          "RunMetrics of the job, as `stiffpath simulate` prints them (summed over the strokes); raises\n"
          "stiffpath.Error when no stroke could be measured");
  py::class_<simulation::StrokeMetrics>(m, "StrokeMetrics", "The metrics of one laser stroke (SI).")
      .def_readonly("index", &simulation::StrokeMetrics::index, "0-based, in job order")
      .def_readonly("start_s", &simulation::StrokeMetrics::start_s)
      .def_readonly("end_s", &simulation::StrokeMetrics::end_s)
      .def_readonly("marked_points", &simulation::StrokeMetrics::marked_points)
      .def_readonly("refusal", &simulation::StrokeMetrics::refusal, "why the line metrics were refused ('' when valid)")
      .def_readonly("sides", &simulation::StrokeMetrics::sides, "straight sides it was measured as (0 when refused)")
      .def_readonly("metrics", &simulation::StrokeMetrics::metrics);

  m.def("simulate", &simulate, py::arg("robot"), py::arg("joints"), py::kw_only(), py::arg("truth") = py::none(),
        py::arg("truth_family") = "structural", py::arg("perturbation") = 0.10, py::arg("seed") = 1,
        py::arg("servo") = "loaded", py::arg("cg_lever") = true, py::arg("sides") = 0,
        py::arg("mass_scale") = simulation::SimulationOptions{}.mass_scale,
        py::arg("damping_ratio") = py::none(),
        py::arg("motor_inertia_kg_m2") = simulation::PlantOptions{}.motor_inertia_kg_m2,
        py::arg("load_feedforward") = simulation::PlantOptions{}.load_feedforward,
        py::arg("load_feedforward_from") = "reference",
        py::arg("settle_s") = simulation::SimulationOptions{}.settle_s,
        py::arg("step_rate_hz") = simulation::PlantOptions{}.step_rate_hz,
        py::arg("servo_bandwidth_hz") = simulation::PlantOptions{}.servo_bandwidth_hz,
        py::arg("mark_rate_hz") = simulation::SimulationOptions{}.mark_rate_hz,
        "Runs joint commands (dtype stiffpath.joints_dtype, e.g. from Compensator.compensate) through the digital twin,\n"
        "as `stiffpath simulate` with the same defaults: servo-driven joints ('loaded': the drives feel the tip\n"
        "through Jᵀ; 'ideal': they track unloaded; bandwidth in Hz, motor inertia in kg·m², load_feedforward the\n"
        "fraction of the platform's load torque fed forward, load_feedforward_from 'reference' (the rigid-body model\n"
        "at the joint commands) or 'command' (the job's own D'Alembert force F, τ = Jᵀ·(−F))) and a compliant tip\n"
        "(damping_ratio ζ) with the\n"
        "true compliance (truth, default true_compliance(robot, perturbation, seed, truth_family)) plus the CG's\n"
        "lever (cg_lever=False puts the CG at the measured point); mass_scale: plant mass / assumed mass.\n"
        "Integrated at step_rate_hz, holding the last command for settle_s s; the mark is recorded at mark_rate_hz\n"
        "and measured stroke by stroke with `sides` straight sides (0: inferred from each stroke's corners).\n"
        "Returns a Simulation.");
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
      .def_readonly("peak_deflection_m", &simulation::RunMetrics::peak_deflection_m)
      .def_readonly("line_strokes", &simulation::RunMetrics::line_strokes, "strokes whose line metrics are in the totals");
  m.def(
      "run_metrics", [](const PySimulation& run, int sides) { return simulation::measure_run(run.result, sides); },
      py::arg("simulation"), py::arg("sides") = 1,
      "Metrics of a simulation's whole mark taken as one path with `sides` straight sides (1: a line, 3: the\n"
      "triangle); for a one-stroke job the same as Simulation.metrics with that many sides.");

  py::class_<evaluation::SideMetrics>(m, "SideMetrics", "One straight side of a marked path (SI).")
      .def_readonly("length_m", &evaluation::SideMetrics::length_m)
      .def_readonly("deviation_area_m2", &evaluation::SideMetrics::deviation_area_m2)
      .def_readonly("max_deviation_m", &evaluation::SideMetrics::max_deviation_m)
      .def_readonly("straightness_m", &evaluation::SideMetrics::straightness_m)
      .def_readonly("point_count", &evaluation::SideMetrics::point_count)
      .def_property_readonly("start_m", [](const evaluation::SideMetrics& s) { return point_array(s.start); },
                             "start on the fitted line (m): the corner, or the free end's extreme projection")
      .def_property_readonly("end_m", [](const evaluation::SideMetrics& s) { return point_array(s.end); },
                             "end on the fitted line (m), likewise")
      .def_readonly("start_is_corner", &evaluation::SideMetrics::start_is_corner)
      .def_readonly("end_is_corner", &evaluation::SideMetrics::end_is_corner);
  py::class_<evaluation::CornerReport>(m, "CornerReport", "A corner between two consecutive sides of a marked path (SI).")
      .def_property_readonly("position_m", [](const evaluation::CornerReport& c) { return point_array(c.position); },
                             "intersection of the two sides' fitted lines (m)")
      .def_readonly("angle_rad", &evaluation::CornerReport::angle_rad, "interior angle (π = no corner, π/3 in an equilateral triangle)")
      .def_readonly("side_before", &evaluation::CornerReport::side_before, "0-based index of the side it ends")
      .def_readonly("side_after", &evaluation::CornerReport::side_after, "0-based index of the side it starts")
      .def_readonly("path_distance_m", &evaluation::CornerReport::path_distance_m,
                    "distance from position_m to the nearest path point (m); None when the points do not reach it (scans)");
  py::class_<evaluation::PathMetrics>(m, "PathMetrics", "Length and deviation from straightness of a marked path (§4.7, SI).")
      .def_readonly("sides", &evaluation::PathMetrics::sides)
      .def_readonly("corners", &evaluation::PathMetrics::corners, "CornerReport of each corner: N − 1 open, N closed (corner k ends side k)")
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
