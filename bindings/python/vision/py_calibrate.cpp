// Python: calibration from a scanned plate, as `stiffpath calibrate fit` does it (registration, marks, identification).
#include <pybind11/stl.h>

#include <filesystem>
#include <optional>
#include <string>

#include "parts.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/job/joint_reader.hpp"
#include "stiffpath/vision/scan/calibrate_from_scan.hpp"

namespace stiffpath::python {

namespace {

//! The most joint records a plate's joint file may hold, as the command line's: 2 M.
constexpr std::size_t kMaxPlateCommands = 2'000'000;

py::object calibrate_fit(const std::string& plate_file, const std::string& scan, const std::string& joints,
                         const std::string& robot_name, const std::optional<std::string>& model,
                         const std::optional<std::string>& output) {
  const kinematics::Robot robot = kinematics::load_robot(robot_name);
  compliance::ModelRequest request;
  if (model) request.model = *model;
  request.how_to_force = "fit a model for this robot";
  std::string model_name = "calibrated_model.json";
  std::filesystem::path out;
  if (output) {
    out = *output;
    model_name = out.stem().string() + "_model.json";
  }
  nlohmann::json report;
  {
    py::gil_scoped_release unlocked;
    const calibration::PlateDesign plate = calibration::load_plate(plate_file);
    const auto commands = job::read_joint_commands(joints, robot.geometry_hash(), kMaxPlateCommands);
    const compliance::LoadedModel base = compliance::load_robot_model(robot, request);
    vision::ScanCalibration cal = vision::calibrate_from_scan(robot, base, plate, commands, scan, model_name);
    cal.report["plate"] = plate_file;
    cal.report["joints"] = joints;
    if (output) {
      vision::write_scan_calibration(cal, out, model_name, out.parent_path() / (out.stem().string() + "_report"));
      cal.report["output"] = *output;
      cal.report["model_file"] = (out.parent_path() / model_name).string();
    }
    report = cal.report;
  }
  return py::module_::import("json").attr("loads")(report.dump());
}

}  // namespace

void add_calibrate(py::module_& m) {
  m.def("calibrate_fit", &calibrate_fit, py::arg("plate"), py::arg("scan"), py::kw_only(), py::arg("joints"),
        py::arg("robot") = "oc-gu", py::arg("model") = py::none(), py::arg("output") = py::none(),
        "Calibrates a robot from a scan of its plate, as `stiffpath calibrate fit`: plate (plate.json), scan (the\n"
        "scanned sheet, a PNG or TIFF recording its resolution), joints (the joint file the plate was marked with),\n"
        "robot (a preset or robot file), model (default: the robot's own). Returns the report as a dict (values\n"
        "before and after with their uncertainty, the misfit per mark, the deflection scale per station, the\n"
        "registration); with output (a robot file's path) also writes the calibrated robot file, its model file\n"
        "<name>_model.json beside it and <name>_report/calibration.json, as the command does.");
}

}  // namespace stiffpath::python
