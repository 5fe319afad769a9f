// The calibration loop end to end on the twin: a plate marked by a platform heavier than its robot file says, drawn as
// a scan, registered, measured and identified: the deflection per unit acceleration comes out as heavy as it is.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <numbers>

#include "cli_runner.hpp"
#include "kept_commands.hpp"
#include "stiffpath/calibration/identify.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/evaluation/segment_distance.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/job/prepared_job.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/simulation/simulator.hpp"
#include "stiffpath/vision/render/calibration_plate.hpp"
#include "stiffpath/vision/scan/plate_marks.hpp"

namespace stiffpath::vision {
namespace {

using kinematics::Vec2;

// The twin's plant is the one simulate() drives: a rigid five-bar on servos (here not loaded by the tip, so the
// servos' own error stays out of the budget) carrying a compliant tip whose compliance is the robot's own model and
// whose mass is 10 % above the robot file's. Marks see m·C: 1.10 along x and y everywhere, no gradient.
TEST(CalibrationLoop, AHeavierPlatformIsFoundFromTheScanOfItsPlate) {
  const auto robot = kinematics::load_robot("oc-gu");
  const std::shared_ptr<compliance::Model> model(compliance::load_robot_model(robot).model.release());
  const calibration::PlateDesign plate =
      calibration::design_plate(robot, compliance::table_region(compliance::robot_table(robot)));
  job::JobSpec spec = job::default_job(robot);
  spec.model.given = model;
  test::Keep keep;
  job::run(job::prepare(spec, job::Program::text(calibration::plate_gcode(plate), "plate.gcode")), &keep);

  simulation::SimulationOptions twin;
  twin.mass_scale = 1.10;
  twin.plant.servo_feels_load = false;
  // The plant integrated at 80 kHz: at its default 20 kHz it rounds the plate's tight arcs (6.6 mm at 0.47 m/s) ~2 µm
  // short of its converged mark, 1 % of their deflection, which the identification would read as a softer field.
  twin.plant.step_rate_hz = 80e3;
  std::vector<calibration::ObservedMark> marked;
  std::size_t next = 0;
  const simulation::JointSource source = [&]() -> std::optional<compensation::JointCommand> {
    if (next == keep.commands.size()) return std::nullopt;
    return keep.commands[next++];
  };
  (void)simulation::simulate(source, robot, model, twin, [&](const simulation::Stroke& s) {
    for (const auto& stroke : plate.strokes) {  // the fiducials are drawn from the plate; strokes by their start
      // (a timing stroke's laser switches at the first 2 kHz sample past its start: within a sample's travel)
      if (!s.commanded.empty() && (s.commanded.front() - stroke.start_m).norm() < 0.5e-3) marked.push_back({stroke.id, s.marked});
    }
  });
  ASSERT_EQ(marked.size(), plate.strokes.size());

  Plate page = calibration_render_plate(plate, marked);
  ScannerBed bed;
  bed.width_m = page.width_m + 16e-3;
  bed.height_m = page.height_m + 16e-3;
  bed.page_at_m = {9e-3, 5e-3};
  bed.page_angle_rad = 1.2 * std::numbers::pi / 180.0;
  page.bed = bed;
  RenderOptions scanner;
  scanner.dpi = 600;
  scanner.seed = 5;
  const RenderedPlate scan = render_plate(page, scanner);
  const PlateObservation seen = observe_calibration_plate(plate, scan.image, scan.dpi, "plate.png");
  EXPECT_LE(seen.registration.residual_rms_m, 10e-6);
  ASSERT_EQ(seen.marks.size(), plate.strokes.size());

  const calibration::Identification id = calibration::identify(keep.commands, robot, *model, plate, seen.marks);
  std::printf("registration %.2f um rms; misfit %.1f -> %.1f um rms (%s, %d iterations)\n",
              seen.registration.residual_rms_m * 1e6, id.rms_before_m * 1e6, id.rms_after_m * 1e6,
              core::to_string(id.stop), id.iterations);
  for (const auto& v : id.values) {
    std::printf("  %-18s %g -> %g +- %g%s\n", v.name.c_str(), v.before, v.after, v.sigma, v.determined ? "" : " (held)");
  }
  // The target: m·C within ±3 % at the plate's points; the damping within ±30 % of the plant's.
  for (const auto& s : id.scales) {
    std::printf("  station (%.1f, %.1f) mm: m*C x %.4f, y %.4f\n", s.point_m.x() * 1e3, s.point_m.y() * 1e3, s.scale.x(),
                s.scale.y());
    EXPECT_NEAR(s.scale.x(), 1.10, 0.033);
    EXPECT_NEAR(s.scale.y(), 1.10, 0.033);
  }
  EXPECT_NEAR(id.after.damping_ratio, robot.tip_damping_ratio, 0.3 * robot.tip_damping_ratio);
  EXPECT_LT(id.rms_after_m, 0.5 * id.rms_before_m);

  // The same through the command line, as a user runs it: the plate's files, the scan as a PNG with its resolution,
  // the joint file; the calibrated robot is one every command accepts, its model carrying the correction.
  test::TempDir dir;
  core::write_file_atomically(dir.path() / "plate.json", calibration::plate_json(plate));
  write_image(dir.path() / "scan.png", scan.image, scan.dpi);
  {
    auto writer = job::make_joint_writer(job::OutputFormat::binary, (dir.path() / "joints.bin").string(), 2000.0,
                                         {robot.name, robot.geometry_hash()});
    for (const auto& c : keep.commands) writer->write(c);
    writer->finish();
  }
  const test::CliResult fit = test::run_cli(
      "calibrate fit plate.json scan.png --joints joints.bin --robot oc-gu -o oc-gu-cal.json --json --centre-line-csv lines.csv",
      dir.path());
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const auto report = fit.json();
  EXPECT_LT(report["rms_after_um"].get<double>(), 0.5 * report["rms_before_um"].get<double>());
  EXPECT_LE(report["registration"]["residual_rms_um"].get<double>(), 10.0);
  // Every centre-line point exported in the robot frame lies on its mark's command (the marks deflect by tens of
  // µm), and its scan position is the registration's image of it: the sheet turned 1.2° and offset on the bed.
  {
    std::ifstream csv(dir.path() / "lines.csv");
    std::string line;
    std::size_t rows = 0;
    double farthest = 0.0, worst_scan = 0.0;
    const double c = std::cos(bed.page_angle_rad), s_ = std::sin(bed.page_angle_rad);
    while (std::getline(csv, line)) {
      if (line.empty() || line[0] == '#' || line.rfind("mark,", 0) == 0) continue;
      std::istringstream in(line);
      std::string id, field;
      std::getline(in, id, ',');
      double v[4];
      for (double& x : v) {
        std::getline(in, field, ',');
        x = std::stod(field) * 1e-3;
      }
      const auto it = std::find_if(plate.strokes.begin(), plate.strokes.end(), [&](const auto& m) { return m.id == id; });
      ASSERT_NE(it, plate.strokes.end()) << line;
      farthest = std::max(farthest, evaluation::polyline_distance(Vec2(v[0], v[1]), it->polyline_m()));
      // The page point (x − x_min, y_max − y) turned about the page's corner and moved to it on the bed.
      const Vec2 page(v[0] - plate.sheet.x_min, plate.sheet.y_max - v[1]);
      const Vec2 on_bed = bed.page_at_m + Vec2(c * page.x() - s_ * page.y(), s_ * page.x() + c * page.y());
      worst_scan = std::max(worst_scan, (on_bed - Vec2(v[2], v[3])).norm());
      ++rows;
    }
    std::size_t points = 0;
    for (const auto& m : seen.marks) points += m.points_m.size();
    EXPECT_EQ(rows, points);
    EXPECT_LT(farthest, 0.3e-3);
    EXPECT_LT(worst_scan, 20e-6) << "the scan positions are not the registration's image of the robot points";
  }
  // The report's figure data: every mark's misfit before and after.
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "oc-gu-cal_report" / "misfit.tsv"));
  const kinematics::Robot calibrated = kinematics::load_robot((dir.path() / "oc-gu-cal.json").string());
  EXPECT_EQ(calibrated.geometry_hash(), robot.geometry_hash());
  EXPECT_NEAR(calibrated.tip_damping_ratio, id.after.damping_ratio, 1e-9);
  const auto corrected = compliance::load_robot_model(calibrated);
  for (const auto& s : id.scales) {  // its model is the robot's, scaled as identified
    const compliance::Mat2 ratio = corrected.model->compliance(s.point_m).cwiseQuotient(model->compliance(s.point_m));
    EXPECT_NEAR(ratio(0, 0), s.scale.x(), 1e-6);  // (to the model file's rounding of the base model's numbers)
    EXPECT_NEAR(ratio(1, 1), s.scale.y(), 1e-6);
  }
  // And the main job runs with it, compensating with the corrected model.
  core::write_file_atomically(dir.path() / "plate.gcode", calibration::plate_gcode(plate));
  const test::CliResult run = test::run_cli("run plate.gcode --robot oc-gu-cal.json --json", dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.json()["model"].get<std::string>().find("oc-gu-cal_model.json"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace stiffpath::vision
