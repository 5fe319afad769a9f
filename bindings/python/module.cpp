// The Python module `stiffpath`: registers the record dtypes, the error type and each part of the API.
#include <pybind11/pybind11.h>

#include "arrays.hpp"
#include "parts.hpp"
#include "stiffpath/core/error.hpp"

namespace py = pybind11;

PYBIND11_MODULE(stiffpath, m) {
  m.doc() =
      "stiffpath: compliance compensation for high-acceleration planar five-bar robots.\n\n"
      "SI units throughout (m, s, rad, N, kg); every argument and field names its unit. Points, forces and\n"
      "joint angles are NumPy arrays whose last axis has length 2: (x, y) in m, (Fx, Fy) in N, (θ1, θ2) in rad.\n"
      "Bad input raises stiffpath.Error, a ValueError whose file, line and column attributes say where.";
  m.attr("__version__") = STIFFPATH_VERSION;

  // stiffpath::Error → stiffpath.Error (a ValueError) with the input's location as attributes.
  static py::handle error_type = PyErr_NewExceptionWithDoc(
      "stiffpath.Error",
      "Bad input (a file, a robot, a program, a point): a ValueError whose message reads 'file:line:column: what'.\n"
      "Attributes: file (str or None), line and column (int, 0 when not known), message (str without the location).",
      PyExc_ValueError, nullptr);
  m.attr("Error") = error_type;
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const stiffpath::Error& e) {
      py::object error = py::reinterpret_borrow<py::object>(error_type)(e.what());
      const auto& where = e.where();
      error.attr("file") = where.file.empty() ? py::object(py::none()) : py::object(py::str(where.file));
      error.attr("line") = where.line;
      error.attr("column") = where.column;
      error.attr("message") = e.message();
      PyErr_SetObject(error_type.ptr(), error.ptr());
    }
  });

  PYBIND11_NUMPY_DTYPE(stiffpath::python::TrajectoryRow, t_s, p_m, v_m_s, a_m_s2, j_m_s3, laser, power, line);
  PYBIND11_NUMPY_DTYPE(stiffpath::python::JointRow, t_s, q_rad, qd_rad_s, qdd_rad_s2, target_m, command_m, force_N,
                       deflection_m, laser, outside_grid, line);
  m.attr("trajectory_dtype") = py::dtype::of<stiffpath::python::TrajectoryRow>();
  m.attr("joints_dtype") = py::dtype::of<stiffpath::python::JointRow>();

  stiffpath::python::add_kinematics(m);
  stiffpath::python::add_compliance(m);
  stiffpath::python::add_motion(m);
  stiffpath::python::add_compensation(m);
  stiffpath::python::add_twin(m);
}
