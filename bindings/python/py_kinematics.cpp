// Python: stiffpath.Robot (presets and robot files) with inverse/forward kinematics and Jacobians over arrays.
#include <pybind11/stl.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "arrays.hpp"
#include "parts.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/kinematics/robot_json.hpp"

namespace stiffpath::python {

namespace {

using kinematics::Robot;

py::object json_to_python(const nlohmann::json& document) {
  return py::module_::import("json").attr("loads")(document.dump());
}

// θ for every point, with the robot's every check; the first refused point raises stiffpath.Error naming it.
py::array_t<double> robot_ik(const Robot& robot, const py::handle& p_m) {
  const auto points = pairs(p_m, "p_m");
  auto q = new_pairs(leading_shape(points));
  const auto n = points.size() / 2;
  const double* in = points.data();
  double* out = q.mutable_data();
  std::string refused;
  std::size_t refused_at = 0;
  {
    py::gil_scoped_release unlocked;
    const kinematics::FiveBar five_bar = robot.five_bar();
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
      const Vec2 p(in[2 * i], in[2 * i + 1]);
      const auto solved = five_bar.solve_inverse(p);
      if (solved.status != kinematics::Reach::ok || !robot.within_limits(solved.q)) {
        refused = robot.refusal(p);
        refused_at = i;
        break;
      }
      out[2 * i] = solved.q.x();
      out[2 * i + 1] = solved.q.y();
    }
  }
  if (!refused.empty()) {
    const Vec2 p(in[2 * refused_at], in[2 * refused_at + 1]);
    throw Error(fmt::format("p_m[{}] {} refused by robot '{}': {}", refused_at, describe_point(p), robot.name, refused));
  }
  return q;
}

py::array_t<double> robot_fk(const Robot& robot, const py::handle& q_rad) {
  const auto angles = pairs(q_rad, "q_rad");
  auto p = new_pairs(leading_shape(angles));
  const double* in = angles.data();
  double* out = p.mutable_data();
  const auto n = static_cast<std::size_t>(angles.size() / 2);
  py::gil_scoped_release unlocked;
  for (std::size_t i = 0; i < n; ++i) {
    Vec2 point;
    try {
      point = robot.forward(Vec2(in[2 * i], in[2 * i + 1]));  // finite, within the joints' ranges (as `kin fk`)
    } catch (const Error& e) {
      throw Error(fmt::format("q_rad[{}]: {}", i, e.message()));
    }
    out[2 * i] = point.x();
    out[2 * i + 1] = point.y();
  }
  return p;
}

py::array_t<double> robot_jacobian(const Robot& robot, const py::handle& q_rad) {
  const auto angles = pairs(q_rad, "q_rad");
  auto jacobians = new_matrices(leading_shape(angles));
  const double* in = angles.data();
  double* out = jacobians.mutable_data();
  const auto n = static_cast<std::size_t>(angles.size() / 2);
  py::gil_scoped_release unlocked;
  const kinematics::FiveBar five_bar = robot.five_bar();
  for (std::size_t i = 0; i < n; ++i) {
    const Mat2 J = five_bar.jacobian(Vec2(in[2 * i], in[2 * i + 1]));
    out[4 * i + 0] = J(0, 0);
    out[4 * i + 1] = J(0, 1);
    out[4 * i + 2] = J(1, 0);
    out[4 * i + 3] = J(1, 1);
  }
  return jacobians;
}

py::array_t<bool> robot_reachable(const Robot& robot, const py::handle& p_m) {
  const auto points = pairs(p_m, "p_m");
  py::array_t<bool> ok(leading_shape(points));
  const double* in = points.data();
  bool* out = ok.mutable_data();
  const kinematics::FiveBar five_bar = robot.five_bar();
  for (py::ssize_t i = 0; i < points.size() / 2; ++i) {
    const auto solved = five_bar.solve_inverse(Vec2(in[2 * i], in[2 * i + 1]));
    out[i] = solved.status == kinematics::Reach::ok && robot.within_limits(solved.q);
  }
  return ok;
}

}  // namespace

void add_kinematics(py::module_& m) {
  m.def("presets", &kinematics::preset_names, "Names of the built-in robots: the thesis's four builds (oc-gu, oc-gl, sc-gu, sc-gl).");

  py::class_<kinematics::JointLimit>(m, "JointLimit", "Limits of one actuated joint (SI).")
      .def_readonly("name", &kinematics::JointLimit::name, "'theta1' or 'theta2'")
      .def_readonly("min_rad", &kinematics::JointLimit::min_rad, "lower position limit (rad)")
      .def_readonly("max_rad", &kinematics::JointLimit::max_rad, "upper position limit (rad)")
      .def_readonly("max_velocity_rad_s", &kinematics::JointLimit::max_velocity_rad_s, "speed limit (rad/s)")
      .def_readonly("max_acceleration_rad_s2", &kinematics::JointLimit::max_acceleration_rad_s2,
                    "acceleration limit (rad/s²)")
      .def("__repr__", [](const kinematics::JointLimit& j) {
        return fmt::format("JointLimit({}: [{:.6g}, {:.6g}] rad, {:.6g} rad/s, {:.6g} rad/s²)", j.name, j.min_rad,
                           j.max_rad, j.max_velocity_rad_s, j.max_acceleration_rad_s2);
      });

  py::class_<Robot>(m, "Robot",
                    "A planar five-bar robot: geometry, working mode, mass, CG height, joint limits and where its\n"
                    "compliance data lives. Built from a preset name (stiffpath.presets()) or a robot file (JSON,\n"
                    "docs/kinematics.md).")
      .def(py::init([](const std::string& preset_or_path) { return kinematics::load_robot(preset_or_path); }),
           py::arg("preset_or_path"),
           "Loads a preset ('oc-gu', …) or a robot file; raises stiffpath.Error naming the file, line and field.")
      .def_readonly("name", &Robot::name)
      .def_readonly("description", &Robot::description)
      .def_readonly("moving_mass_kg", &Robot::moving_mass_kg, "mass the platform carries (kg), thesis §4.2")
      .def_readonly("tip_damping_ratio", &Robot::tip_damping_ratio, "damping ratio of the platform's modes (robot file; 0.05 when it gives none)")
      .def_readonly("cg_label", &Robot::cg_label, "name of the centre-of-gravity position ('G_U', 'G_L')")
      .def_readonly("cg_height_m", &Robot::cg_height_m, "height of the CG above the measured point G (m)")
      .def_property_readonly("joints", [](const Robot& r) { return std::vector<kinematics::JointLimit>(r.joints.begin(), r.joints.end()); },
                             "limits of θ1 and θ2 (list of two JointLimit)")
      .def_property_readonly("home_m", [](const Robot& r) -> py::object {
        return r.home_m ? py::object(py::make_tuple(r.home_m->x(), r.home_m->y())) : py::object(py::none());
      }, "home position of the end point (x, y) in m, or None")
      .def_readonly("preset", &Robot::preset, "True for a built-in robot")
      .def_property_readonly("source", &Robot::source, "'preset oc-gu' or the robot file's path")
      .def_property_readonly("geometry_hash", &Robot::geometry_hash, "SHA-256 of the geometry (model files record it)")
      .def("to_dict", [](const Robot& r) { return json_to_python(kinematics::to_json(r)); },
           "The robot in the robot-file format (a dict; units in the key names).")
      .def("ik", &robot_ik, py::arg("p_m"),
           "Inverse kinematics (thesis eq. 2.2 for the thesis's robot) in the robot's working mode.\n\n"
           "p_m: end points (..., 2) in m. Returns θ (..., 2) in rad. Every point is checked for reach (singularity\n"
           "margin) and joint ranges; the first refused point raises stiffpath.Error naming its index and the reason.")
      .def("fk", &robot_fk, py::arg("q_rad"),
           "Forward kinematics (thesis eq. 2.1): joint angles (..., 2) in rad → end points (..., 2) in m.")
      .def("jacobian", &robot_jacobian, py::arg("q_rad"),
           "Jacobian J = ∂p/∂θ at joint angles (..., 2) in rad → (..., 2, 2) in m/rad, J[..., i, j] = ∂p_i/∂θ_j.")
      .def("reachable", &robot_reachable, py::arg("p_m"),
           "Whether each point (..., 2) in m passes the reach and joint-range checks of ik (bool array (...)).")
      .def("refusal", [](const Robot& r, double x_m, double y_m) { return r.refusal(Vec2(x_m, y_m)); },
           py::arg("x_m"), py::arg("y_m"), "Why the point (m) is refused, in words; '' when ik accepts it.")
      .def("__repr__", [](const Robot& r) { return fmt::format("Robot('{}', {})", r.name, r.source()); });
}

}  // namespace stiffpath::python
