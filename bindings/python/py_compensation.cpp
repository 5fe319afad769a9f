// Python: stiffpath.Compensator (the real-time step, thesis fig. 4.3) and compensate (a whole trajectory → joints).
#include <pybind11/stl.h>

#include <fmt/format.h>

#include "arrays.hpp"
#include "parts.hpp"
#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compensation/run_filters.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/prepared_job.hpp"
#include "stiffpath/motion/sampler.hpp"

namespace stiffpath::python {

namespace {

using compensation::Compensator;
using compensation::JointCommand;

struct PyCompensator {
  std::shared_ptr<Compensator> compensator;
  PyModel model;
};

PyCompensator make_compensator(const kinematics::Robot& robot, const std::optional<PyModel>& model, double gain,
                               bool enabled, bool check_limits, const std::string& method,
                               std::optional<double> damping_ratio, bool force_model) {
  PyModel used = model ? *model : to_py_model(compliance::load_robot_model(robot));
  if (model) {
    compliance::LoadedModel check{nullptr, used.provenance, used.label};
    compliance::check_model_geometry(check, robot, force_model, "pass force_model=True");
  }
  const compensation::CompensatorOptions options{.gain = gain,
                                                 .enabled = enabled,
                                                 .check_limits = check_limits,
                                                 .method = core::parse_enum<compensation::Method>(method),
                                                 .damping_ratio = damping_ratio};
  auto compensator = std::make_shared<Compensator>(robot, used.model, options);
  return {std::move(compensator), std::move(used)};
}

// A whole trajectory through the job `run` makes from this compensator's settings: the same reference filters
// (their defaults: job::JobSpec's), the same checks, the same commands.
py::array compensate(const PyCompensator& c, const py::handle& trajectory_in, const std::string& acceleration,
                     double rate_hz, std::optional<double> smooth_s, const std::string& shaper, const std::string& label) {
  const auto trajectory = trajectory_records(trajectory_in, "trajectory");
  const compensation::CompensatorOptions& o = c.compensator->options();
  job::JobSpec spec = job::default_job(c.compensator->robot());
  spec.model.given = c.model.model;
  spec.model.given_label = c.model.label;
  spec.compensate = o.enabled;
  spec.gain = o.gain;
  spec.check_limits = o.check_limits;
  spec.method = o.method;
  spec.damping_ratio = o.damping_ratio;
  spec.acceleration = core::parse_enum<job::AccelerationSource>(acceleration);
  spec.smooth_s = smooth_s;
  spec.shaper = core::parse_enum<compensation::FilterKind>(shaper);
  spec.plan.rate_hz = rate_hz;
  std::vector<motion::TrajectorySample> samples;
  samples.reserve(static_cast<std::size_t>(trajectory.size()));
  for (py::ssize_t i = 0; i < trajectory.size(); ++i) samples.push_back(to_sample(trajectory.data()[i]));
  RowWriter writer;
  {
    py::gil_scoped_release unlocked;
    const job::PreparedJob prepared = job::prepare(std::move(spec), job::Program::samples(std::move(samples), label));
    job::run(prepared, &writer);
  }
  return writer.array();
}

Vec2 pair_of(const py::handle& value, const char* what) {
  const auto a = pairs(value, what);
  if (a.size() != 2) throw py::value_error(fmt::format("{}: expected 2 numbers", what));
  return {a.data()[0], a.data()[1]};
}

}  // namespace

void add_compensation(py::module_& m) {
  py::class_<JointCommand>(m, "JointCommand", "The compensator's output for one sample (SI).")
      .def_readonly("t_s", &JointCommand::t_s)
      .def_property_readonly("q_rad", [](const JointCommand& c) { return py::make_tuple(c.q_rad.x(), c.q_rad.y()); }, "θ1, θ2 = IK(p_cmd)")
      .def_property_readonly("qd_rad_s", [](const JointCommand& c) { return py::make_tuple(c.qd_rad_s.x(), c.qd_rad_s.y()); }, "ω1, ω2")
      .def_property_readonly("qdd_rad_s2", [](const JointCommand& c) { return py::make_tuple(c.qdd_rad_s2.x(), c.qdd_rad_s2.y()); }, "α1, α2")
      .def_property_readonly("target_m", [](const JointCommand& c) { return py::make_tuple(c.target_m.x(), c.target_m.y()); }, "planned point p")
      .def_property_readonly("command_m", [](const JointCommand& c) { return py::make_tuple(c.command_m.x(), c.command_m.y()); }, "corrected target p_cmd = p − k·Δ")
      .def_property_readonly("force_N", [](const JointCommand& c) { return py::make_tuple(c.force_N.x(), c.force_N.y()); }, "D'Alembert force F = −m·a (eq. 4.4)")
      .def_property_readonly("deflection_m", [](const JointCommand& c) { return py::make_tuple(c.deflection_m.x(), c.deflection_m.y()); }, "predicted Δ = C(p)·F")
      .def_property_readonly("load_torque_Nm", [](const JointCommand& c) { return py::make_tuple(c.load_torque_Nm.x(), c.load_torque_Nm.y()); },
                             "the platform's inertial load on the joints, τ = Jᵀ·m·a (N·m): the drives' torque feed-forward")
      .def_property_readonly("status", [](const JointCommand& c) { return std::string(compensation::describe(c.status)); }, "'ok' or why the command must not be sent")
      .def_property_readonly("ok", [](const JointCommand& c) { return c.status == compensation::Status::ok; })
      .def_readonly("joint", &JointCommand::joint, "offending joint (0, 1) for a joint-limit status, else −1")
      .def_readonly("outside_grid", &JointCommand::outside_grid)
      .def("__repr__", [](const JointCommand& c) {
        return fmt::format("JointCommand(t_s={:.6g}, q_rad=({:.9g}, {:.9g}), status='{}')", c.t_s, c.q_rad.x(), c.q_rad.y(),
                           compensation::describe(c.status));
      });

  py::class_<PyCompensator>(m, "Compensator",
                            "The compensation step of thesis fig. 4.3 for one robot and compliance model: F = −m·a at the\n"
                            "CG (eq. 4.4), Δ = C(p)·F (eqs. 4.6–4.7, 4.12), p_cmd = p − k·Δ, θ = IK(p_cmd), then the\n"
                            "reach and joint-limit checks.")
      .def(py::init(&make_compensator), py::arg("robot"), py::arg("model") = py::none(), py::arg("gain") = job::JobSpec{}.gain,
           py::arg("enabled") = true, py::arg("check_limits") = true, py::kw_only(),
           py::arg("method") = std::string(core::enum_name(job::JobSpec{}.method)),
           py::arg("damping_ratio") = py::none(), py::arg("force_model") = false,
           "robot: a Robot. model: a Model (default: the robot's own, as the CLI's run). gain: k (≥ 0).\n"
           "enabled=False gives the uncompensated command p_cmd = p. A model fitted for another geometry is refused.\n"
           "method: 'dynamic' (default, as `stiffpath run`: the damped tip's lag inverted, p_cmd = p + k·δ) or\n"
           "'quasi-static' (the thesis's p_cmd = p − k·C(p)·F). damping_ratio: ζ of the tip's modes the dynamic\n"
           "method assumes (0 … 2; default None: the robot file's tip_damping_ratio, 0.05 when it gives none).\n"
           "force_model=True: accept a model fitted for another robot geometry.")
      .def_property_readonly("model", [](const PyCompensator& c) { return c.model; })
      .def_property_readonly("robot", [](const PyCompensator& c) { return c.compensator->robot(); })
      .def("step",
           [](const PyCompensator& c, double t_s, const py::handle& p_m, const py::handle& v_m_s, const py::handle& a_m_s2,
              const py::handle& j_m_s3, const py::handle& s_m_s4) {
             compensation::TaskSample s;
             s.t_s = t_s;
             s.position_m = pair_of(p_m, "p_m");
             s.velocity_m_s = pair_of(v_m_s, "v_m_s");
             s.acceleration_m_s2 = pair_of(a_m_s2, "a_m_s2");
             s.jerk_m_s3 = pair_of(j_m_s3, "j_m_s3");
             s.snap_m_s4 = pair_of(s_m_s4, "s_m_s4");
             return c.compensator->step(s);
           },
           py::arg("t_s"), py::arg("p_m"), py::arg("v_m_s") = py::make_tuple(0.0, 0.0),
           py::arg("a_m_s2") = py::make_tuple(0.0, 0.0), py::arg("j_m_s3") = py::make_tuple(0.0, 0.0),
           py::arg("s_m_s4") = py::make_tuple(0.0, 0.0),
           "One sample of the planned path (t in s; p, v, a, jerk, snap as (x, y) pairs in m, m/s, m/s², m/s³, m/s⁴) →\n"
           "JointCommand. Never raises for a bad sample: check .ok / .status, as a servo loop would.")
      .def_property_readonly("method", [](const PyCompensator& c) { return std::string(core::enum_name(c.compensator->options().method)); })
      .def_property_readonly("damping_ratio", [](const PyCompensator& c) { return *c.compensator->options().damping_ratio; })
      .def("compensate", &compensate, py::arg("trajectory"), py::arg("acceleration") = "analytic",
           py::arg("rate_hz") = motion::default_sample_rate_hz, py::kw_only(),
           py::arg("smooth_s") = py::none(), py::arg("shaper") = "none",
           py::arg("label") = "<trajectory>",
           "A whole trajectory (dtype stiffpath.trajectory_dtype, e.g. from plan) → joint commands (dtype\n"
           "stiffpath.joints_dtype: t_s, q_rad, qd_rad_s, qdd_rad_s2, target_m, command_m, force_N, deflection_m,\n"
           "laser, power, outside_grid, line), as `stiffpath run` writes them, with run's reference filters before\n"
           "compensation: smooth_s (s; default None: 0.008 when compensating, two moving averages of half that width\n"
           "for continuous jerk and snap, and 0 without compensation; 0 = off) and shaper ('none', 'zv', 'zvd': an input shaper following the tip's frequency). The\n"
           "filters lengthen the job by their delay. acceleration: 'analytic' (the profile's) or\n"
           "'numeric' (second difference of the positions at rate_hz, the thesis's §4.3). The first refused sample\n"
           "raises stiffpath.Error naming the label, the G-code line, the time and the limit.");
}

}  // namespace stiffpath::python
