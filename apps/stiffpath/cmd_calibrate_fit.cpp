// `stiffpath calibrate fit`: a scanned plate and its joint file in, the robot identified from its own marks out.
#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "robot_flags.hpp"
#include "vision_resources.hpp"
#include "stiffpath/calibration/calibrated_robot.hpp"
#include "stiffpath/calibration/identify.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/distinct_files.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/job/joint_reader.hpp"
#include "stiffpath/vision/scan/calibrate_from_scan.hpp"

namespace stiffpath::cli {

namespace {

//! The most joint records a plate's joint file may hold: 2 M (1000 s at 2 kHz; a plate takes well under a minute).
constexpr std::size_t kMaxPlateCommands = 2'000'000;

struct FitArgs {
  std::string plate, scan, joints, robot, output, report_dir, centre_line_csv;
  ModelFlags model;
  bool json = false;
};

// One row per measured centre-line point of every plate mark, in marking order: its id, the point in the robot
// frame (mm) and where it lies on the scan (mm from the image's top-left corner, y down).
std::string centre_line_csv(const std::string& scan, const vision::PlateObservation& seen) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out),
                 "# centre lines of the plate's marks measured on {}: x_mm, y_mm in the robot frame (registered by the "
                 "fiducials), scan_x_mm, scan_y_mm on the scan from its top-left corner, y down\nmark,x_mm,y_mm,scan_x_mm,scan_y_mm\n",
                 scan);
  for (const auto& m : seen.marks) {
    for (const auto& p : m.points_m) {
      const Eigen::Vector2d q = seen.registration.to_scan(p);
      fmt::format_to(std::back_inserter(out), "{},{:.4f},{:.4f},{:.4f},{:.4f}\n", m.id, p.x() * 1e3, p.y() * 1e3, q.x() * 1e3, q.y() * 1e3);
    }
  }
  return fmt::to_string(out);
}

void fit(const FitArgs& a) {
  const auto robot = load_robot_flag(a.robot);
  const std::filesystem::path out(a.output);
  const std::string model_name = out.stem().string() + "_model.json";
  const std::filesystem::path model_path = out.parent_path() / model_name;
  const std::filesystem::path report_dir =
      a.report_dir.empty() ? out.parent_path() / (out.stem().string() + "_report") : std::filesystem::path(a.report_dir);
  core::check_distinct_files(
      robot_inputs(robot, true, {{"plate", a.plate}, {"scan", a.scan}, {"--joints", a.joints}, {"--model", a.model.model}}),
      {{"-o", a.output}, {"(the model file)", model_path.string()}, {"(the report)", (report_dir / "calibration.json").string()},
       {"(the report's misfit data)", (report_dir / "misfit.tsv").string()}, {"--centre-line-csv", a.centre_line_csv}});
  const calibration::PlateDesign plate = calibration::load_plate(a.plate);
  const auto commands = job::read_joint_commands(a.joints, robot.geometry_hash(), kMaxPlateCommands);
  const compliance::LoadedModel base = compliance::load_robot_model(robot, model_request(a.model));
  core::check_output_directory(report_dir.string());
  vision::ScanCalibration cal;
  try {
    cal = vision::calibrate_from_scan(robot, base, plate, commands, a.scan, model_name);
  } catch (const Error& e) {
    if (!e.where().file.empty()) throw;
    throw Error(SourceLocation{a.plate}, e.message());
  }
  cal.report["plate"] = a.plate;
  cal.report["joints"] = a.joints;
  // The centre lines before the calibration's files, whose robot file is written last: it marks a finished fit.
  if (!a.centre_line_csv.empty()) core::write_file_atomically(a.centre_line_csv, centre_line_csv(a.scan, cal.seen));
  vision::write_scan_calibration(cal, out, model_name, report_dir);
  const vision::PlateObservation& seen = cal.seen;
  const calibration::Identification& id = cal.identified;
  const auto& r = seen.registration;
  nlohmann::json report = cal.report;
  if (a.json) {
    report["output"] = a.output;
    report["model_file"] = model_path.string();
    print_json(report);
    return;
  }
  fmt::print("{}: {} marks measured on {} (registered by {} fiducials{}, residual {:.1f} um rms)\n", robot.name,
             seen.marks.size(), a.scan, r.fiducials, r.mirrored ? ", mirrored" : "", r.residual_rms_m * 1e6);
  for (const auto& w : seen.warnings) fmt::print("  warning: {}\n", w);
  fmt::print("  misfit of the marks {:.1f} um rms before, {:.1f} um after ({}, {} iterations)\n", id.rms_before_m * 1e6,
             id.rms_after_m * 1e6, core::to_string(id.stop), id.iterations);
  for (const auto& v : id.values) {
    if (v.determined) {
      fmt::print("  {:<18} {:>10.5g} -> {:>10.5g} +- {:.2g}\n", v.name, v.before, v.after, v.sigma);
    } else {
      fmt::print("  {:<18} {:>10.5g}    held: the plate does not determine it\n", v.name, v.before);
    }
  }
  fmt::print("wrote {}, {} and {}\n", a.output, model_path.string(), (report_dir / "calibration.json").string());
}

}  // namespace

void add_calibrate_fit_command(CLI::App& app) {
  auto* calibrate = app.add_subcommand("calibrate", "Calibrate the robot from its own marks");
  calibrate->require_subcommand(1);
  auto a = std::make_shared<FitArgs>();
  auto* cmd = calibrate->add_subcommand("fit", "Identify the robot from a scan of its calibration plate");
  cmd->add_option("plate", a->plate, "The plate's description (plate.json from calibrate plate)")->required();
  cmd->add_option("scan", a->scan, "The scanned sheet (PNG or TIFF with its resolution, 1200 dpi recommended)")->required();
  cmd->add_option("--joints", a->joints, "The joint file the plate was marked with (stiffpath run plate.gcode -o ...)")
      ->required();
  add_robot_flag(cmd, a->robot);
  add_model_flags(cmd, a->model);
  cmd->add_option("-o,--output", a->output, "The calibrated robot file to write (its model file beside it: <name>_model.json)")
      ->check(output_name())
      ->required();
  cmd->add_option("--report-dir", a->report_dir, "Folder for calibration.json (default: <output>_report beside it)");
  cmd->add_option("--centre-line-csv", a->centre_line_csv,
                  "Also write every mark's measured centre line: mark,x_mm,y_mm (robot frame),scan_x_mm,scan_y_mm (scan)")
      ->check(output_name());
  cmd->add_flag("--json", a->json, "Print the report as JSON");
  cmd->callback([a] { within_resources(a->output, "calibrating from the scan", 0.0, [&] { fit(*a); }); });
}

}  // namespace stiffpath::cli
