// `stiffpath calibrate plate`: writes the calibration plate (G-code and its description) for a robot's measured region.
#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "commands.hpp"
#include "robot_flags.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/distinct_files.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::cli {

namespace {
struct PlateArgs {
  std::string robot, output, accel = "5g";
  bool json = false;
};

void plate(const PlateArgs& a) {
  const auto robot = load_robot_flag(a.robot);
  calibration::PlateOptions options;
  try {
    options.acceleration_m_s2 = units::parse_acceleration_m_s2(a.accel);
  } catch (const Error& e) {
    throw Error("--accel: " + e.message());
  }
  const calibration::PlateDesign design = calibration::design_plate(robot, calibration::plate_region(robot), options);
  const std::filesystem::path dir(a.output);
  core::check_distinct_files(robot_inputs(robot, true), {{"-o", (dir / "plate.gcode").string()}, {"-o", (dir / "plate.json").string()}});
  core::create_output_directory(dir);
  core::write_file_atomically(dir / "plate.gcode", calibration::plate_gcode(design, options));
  core::write_file_atomically(dir / "plate.json", calibration::plate_json(design));
  std::size_t ringing = 0, timing = 0, arcs = 0;
  for (const auto& m : design.strokes) {
    (m.kind == calibration::StrokeKind::ringing ? ringing : m.kind == calibration::StrokeKind::timing ? timing : arcs) += 1;
  }
  if (a.json) {
    print_json({{"robot", robot.name},
                {"fiducials", design.fiducials.size()},
                {"marks", design.strokes.size()},
                {"ringing_strokes", ringing},
                {"timing_strokes", timing},
                {"arcs", arcs},
                {"gcode", (dir / "plate.gcode").string()},
                {"plate", (dir / "plate.json").string()}});
    return;
  }
  fmt::print("calibration plate for {}: {} fiducials and {} marks ({} ringing strokes, {} timing strokes, {} arcs) over "
             "x [{:.1f}, {:.1f}] mm, y [{:.1f}, {:.1f}] mm\n",
             robot.name, design.fiducials.size(), design.strokes.size(), ringing, timing, arcs, units::m_to_mm(design.area.x_min),
             units::m_to_mm(design.area.x_max), units::m_to_mm(design.area.y_min), units::m_to_mm(design.area.y_max));
  fmt::print("wrote {} and {}\nnext: stiffpath run {} --robot {} -o {} ; mark it, scan the sheet at 1200 dpi, then "
             "stiffpath calibrate fit\n",
             (dir / "plate.gcode").string(), (dir / "plate.json").string(), (dir / "plate.gcode").string(),
             a.robot.empty() ? robot.name : a.robot, (dir / "plate_joints.csv").string());
}
}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto* calibrate = app.add_subcommand("calibrate", "Calibrate the robot from its own marks: a plate to mark, then a fit");
  calibrate->require_subcommand(1);
  auto a = std::make_shared<PlateArgs>();
  auto* plate_cmd = calibrate->add_subcommand("plate", "Write a calibration plate (plate.gcode, plate.json) for a robot");
  add_robot_flag(plate_cmd, a->robot);
  plate_cmd->add_option("--accel", a->accel, "The plate's highest acceleration, e.g. 5g or 49 (m/s^2)")->capture_default_str();
  plate_cmd->add_option("-o,--output", a->output, "Directory to write plate.gcode and plate.json into")->required();
  plate_cmd->add_flag("--json", a->json, "Print a JSON summary");
  plate_cmd->callback([a] { plate(*a); });
  // fit reads the scan, so it runs in stiffpath-vision (the program that links OpenCV), its arguments unchanged.
  auto* fit_cmd = calibrate->add_subcommand("fit", "Identify the robot from a scan of its calibration plate (run by stiffpath-vision)");
  fit_cmd->prefix_command();
  fit_cmd->set_help_flag();
  fit_cmd->callback([fit_cmd] {
    std::vector<std::string> words{"calibrate", "fit"};
    const auto rest = fit_cmd->remaining();
    words.insert(words.end(), rest.begin(), rest.end());
    run_vision_tool(words);
  });
}

}  // namespace stiffpath::cli
