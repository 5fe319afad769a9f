// Python: the calibration plate for a robot, as `stiffpath calibrate plate` lays it out (the fit is stiffpath.vision's).
#include <pybind11/stl.h>

#include <filesystem>
#include <optional>
#include <string>

#include "parts.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"

namespace stiffpath::python {

namespace {

py::dict calibration_plate(const py::handle& robot_arg, double accel_m_s2, const std::optional<std::string>& output_dir) {
  const kinematics::Robot robot = py::isinstance<py::str>(robot_arg) ? kinematics::load_robot(robot_arg.cast<std::string>())
                                                                      : robot_arg.cast<kinematics::Robot>();
  calibration::PlateOptions options;
  options.acceleration_m_s2 = accel_m_s2;
  const calibration::PlateDesign design = calibration::design_plate(robot, calibration::plate_region(robot), options);
  py::dict out;
  out["gcode"] = calibration::plate_gcode(design, options);
  out["plate"] = calibration::plate_json(design);
  out["fiducials"] = design.fiducials.size();
  out["strokes"] = design.strokes.size();
  if (output_dir) {
    const std::filesystem::path dir(*output_dir);
    core::create_output_directory(dir);
    core::write_file_atomically(dir / "plate.gcode", out["gcode"].cast<std::string>());
    core::write_file_atomically(dir / "plate.json", out["plate"].cast<std::string>());
  }
  return out;
}

}  // namespace

void add_calibration(py::module_& m) {
  m.def("calibration_plate", &calibration_plate, py::arg("robot") = "oc-gu", py::kw_only(),
        py::arg("accel_m_s2") = calibration::PlateOptions{}.acceleration_m_s2, py::arg("output_dir") = py::none(),
        "The calibration plate for a robot, as `stiffpath calibrate plate`: a dict with 'gcode' (the program to run\n"
        "and mark: stiffpath.run(gcode=...)), 'plate' (plate.json's text, for stiffpath.vision.calibrate_fit) and the\n"
        "counts of fiducials and strokes; with output_dir, also written there as plate.gcode and plate.json.\n"
        "robot: a Robot or a preset/robot file; accel_m_s2: the plate's highest acceleration.");
}

}  // namespace stiffpath::python
