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

  // NumPy is imported when the first array is made, not here (it would triple the module's import time).
  m.def(
      "__getattr__",
      [](const std::string& name) -> py::object {
        if (name == "trajectory_dtype" || name == "joints_dtype") {
          stiffpath::python::ensure_record_dtypes();
          return name == "trajectory_dtype" ? py::dtype::of<stiffpath::python::TrajectoryRow>()
                                            : py::dtype::of<stiffpath::python::JointRow>();
        }
        if (name == "joint_file_dtype") return stiffpath::python::joint_file_dtype();
        if (name == "vision") {
          // The scan part is a module of its own (_stiffpath_vision, beside this one), built with OpenCV: imported
          // here, on first use, so that `import stiffpath` does not load OpenCV.
          py::module_ vision;
          try {
            vision = py::module_::import("_stiffpath_vision");
          } catch (py::error_already_set& e) {
            if (!e.matches(PyExc_ModuleNotFoundError)) throw;
            throw py::attribute_error("stiffpath.vision: this build of stiffpath has no vision part (it needs OpenCV)");
          }
          py::module_::import("sys").attr("modules")["stiffpath.vision"] = vision;
          py::module_::import("stiffpath").attr("vision") = vision;
          return vision;
        }
        throw py::attribute_error("module 'stiffpath' has no attribute '" + name + "'");
      },
      "trajectory_dtype, joints_dtype and joint_file_dtype, made on first use, and vision, imported on first use (PEP 562).");

  m.attr("joint_file_fields") = stiffpath::python::joint_file_fields();
  stiffpath::python::add_kinematics(m);
  stiffpath::python::add_compliance(m);
  stiffpath::python::add_motion(m);
  stiffpath::python::add_compensation(m);
  stiffpath::python::add_twin(m);
  stiffpath::python::add_job(m);
  stiffpath::python::add_calibration(m);
}
