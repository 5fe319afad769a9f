// calibrate_from_scan(): the scan registered and measured, the robot identified from it, its files made.
#include "stiffpath/vision/scan/calibrate_from_scan.hpp"

#include <fmt/format.h>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/report/calibration_plots.hpp"

namespace stiffpath::vision {

ScanCalibration calibrate_from_scan(const kinematics::Robot& robot, const compliance::LoadedModel& base,
                                    const calibration::PlateDesign& plate,
                                    const std::vector<compensation::JointCommand>& commands,
                                    const std::filesystem::path& scan, const std::string& model_file_name,
                                    const PlateScanOptions& options) {
  if (plate.geometry_sha256 != robot.geometry_hash()) {
    throw Error(fmt::format("the plate was laid out for robot '{}' of another geometry than '{}'", plate.robot, robot.name));
  }
  ScanCalibration out;
  out.seen = observe_calibration_plate(plate, scan, options);
  out.identified = calibration::identify(commands, robot, *base.model, plate, out.seen.marks);
  out.files = calibration::calibrated_robot(robot, base, out.identified, model_file_name);
  out.report = calibration::identification_json(out.identified);
  const PlateRegistration& r = out.seen.registration;
  out.report["registration"] = {{"fiducials", r.fiducials},
                                {"mirrored", r.mirrored},
                                {"residual_rms_um", r.residual_rms_m * 1e6},
                                {"residual_max_um", r.residual_max_m * 1e6}};
  out.report["warnings"] = out.seen.warnings;
  out.report["robot"] = robot.name;
  out.report["scan"] = scan.string();
  return out;
}

void write_scan_calibration(const ScanCalibration& calibration, const std::filesystem::path& robot_file,
                            const std::string& model_file_name, const std::filesystem::path& report_dir) {
  core::check_output_directory(report_dir);
  core::write_file_atomically(robot_file.parent_path() / model_file_name, calibration.files.model.dump(2) + "\n");
  const std::string robot_text = calibration.files.robot.dump(2) + "\n";
  (void)kinematics::parse_robot(robot_text, core::DataRef{robot_file.string(), false});
  core::create_output_directory(report_dir);
  nlohmann::json doc = calibration.report;
  const bool drawn = report::plot_calibration_misfit(report_dir, "misfit", calibration.identified);
  doc["misfit_data"] = "misfit.tsv";
  doc["misfit_figure"] = drawn ? nlohmann::json("misfit.svg") : nlohmann::json(nullptr);
  core::write_file_atomically(report_dir / "calibration.json", doc.dump(2) + "\n");
  core::write_file_atomically(robot_file, robot_text);
}

}  // namespace stiffpath::vision
