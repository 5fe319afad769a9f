// Calibration from a scanned plate, in one call: registration, the marks measured, the robot identified, its files.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "stiffpath/calibration/calibrated_robot.hpp"
#include "stiffpath/calibration/identify.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/vision/scan/plate_marks.hpp"

namespace stiffpath::vision {

//! What a calibration from a scan found and would write.
struct ScanCalibration {
  PlateObservation seen;                  //!< the registration and the measured marks (robot frame)
  calibration::Identification identified;
  calibration::CalibratedRobot files;     //!< the robot file and model file documents
  nlohmann::json report;                  //!< identification_json with the registration and the scan's warnings
};

//! `stiffpath calibrate fit` without its files: registers `scan` by the plate's fiducials, measures every stroke,
//! identifies the robot against `commands` (the plate's joint file) through `base` (the robot's compliance model),
//! and makes the calibrated robot's documents, whose compliance.model names `model_file_name`. Throws
//! stiffpath::Error for a plate laid out for another geometry than the robot's, and as its steps do.
ScanCalibration calibrate_from_scan(const kinematics::Robot& robot, const compliance::LoadedModel& base,
                                    const calibration::PlateDesign& plate,
                                    const std::vector<compensation::JointCommand>& commands,
                                    const std::filesystem::path& scan, const std::string& model_file_name,
                                    const PlateScanOptions& options = {});

//! Writes the calibration's files, each atomically: the model file (`robot_file`'s folder / `model_file_name` as
//! given to calibrate_from_scan), `report_dir`/misfit.tsv and, with gnuplot, misfit.svg and .png (every mark's
//! misfit before and after: report::plot_calibration_misfit), `report_dir`/calibration.json (the folder made when
//! missing), and last the robot file, once it parses as every command will read it.
void write_scan_calibration(const ScanCalibration& calibration, const std::filesystem::path& robot_file,
                            const std::string& model_file_name, const std::filesystem::path& report_dir);

}  // namespace stiffpath::vision
