// The calibration loop end to end on the twin: a plate marked by a platform heavier than its robot file says, drawn as
// a scan, registered, measured and identified: the deflection per unit acceleration comes out as heavy as it is.
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include "cli_runner.hpp"
#include "stiffpath/calibration/identify.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/job/prepared_job.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/simulation/simulator.hpp"
#include "stiffpath/vision/render/calibration_plate.hpp"
#include "stiffpath/vision/scan/plate_marks.hpp"

namespace stiffpath::vision {
namespace {

class Keep final : public job::JointWriter {
 public:
  void write(const compensation::JointCommand& c) override { commands.push_back(c); }
  void finish() override {}
  std::vector<compensation::JointCommand> commands;
};

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
  Keep keep;
  job::run(job::prepare(spec, job::Program::text(calibration::plate_gcode(plate), "plate.gcode")), &keep);

  simulation::SimulationOptions twin;
  twin.mass_scale = 1.10;
  twin.plant.servo_feels_load = false;
  std::vector<calibration::ObservedMark> marked;
  std::size_t next = 0;
  const simulation::JointSource source = [&]() -> std::optional<compensation::JointCommand> {
    if (next == keep.commands.size()) return std::nullopt;
    return keep.commands[next++];
  };
  (void)simulation::simulate(source, robot, model, twin, [&](const simulation::Stroke& s) {
    for (const auto& stroke : plate.strokes) {  // the fiducials are drawn from the plate; strokes by their start
      if (!s.commanded.empty() && (s.commanded.front() - stroke.start_m).norm() < 1e-6) marked.push_back({stroke.id, s.marked});
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
      "calibrate fit plate.json scan.png --joints joints.bin --robot oc-gu -o oc-gu-cal.json --json", dir.path());
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const auto report = fit.json();
  EXPECT_LT(report["rms_after_um"].get<double>(), 0.5 * report["rms_before_um"].get<double>());
  EXPECT_LE(report["registration"]["residual_rms_um"].get<double>(), 10.0);
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
