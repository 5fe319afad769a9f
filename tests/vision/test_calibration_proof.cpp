// The calibration's proof on the twin: a robot whose truth is not what its file says marks its plate; the scan
// calibrates it; held-out jobs (held_out_jobs.hpp) are then marked nearly as well as with the truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "held_out_jobs.hpp"
#include "kept_commands.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/compliance/corrected_model.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/least_squares.hpp"
#include "stiffpath/evaluation/segment_distance.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/job/prepared_job.hpp"
#include "stiffpath/simulation/cg_lever.hpp"
#include "stiffpath/simulation/simulator.hpp"
#include "stiffpath/simulation/twin_models.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/vision/render/calibration_plate.hpp"

namespace stiffpath::vision {
namespace {

using kinematics::Vec2;

// One twin: its truth (C_true of a seed, a platform 10 % lighter than the robot file says, twice its damping, a
// laser that lights 1 ms and goes dark 0.5 ms after it is told to).
struct Twin {
  kinematics::Robot robot;
  std::shared_ptr<const compliance::Model> truth;
  simulation::SimulationOptions options;
  int on_delay_samples = 2, off_delay_samples = 1;  // at the joint file's 2 kHz
  [[nodiscard]] double on_delay_s() const { return on_delay_samples / 2000.0; }
  [[nodiscard]] double off_delay_s() const { return off_delay_samples / 2000.0; }
};

// The laser as the twin's lights it: each pulse the commands ask for, from sample a to b, lights from a + on to b + off.
std::vector<compensation::JointCommand> lit_late(std::vector<compensation::JointCommand> c, int on, int off) {
  const std::size_t n = c.size();
  std::vector<bool> lit(n, false);
  for (std::size_t a = 0; a < n;) {
    if (!c[a].laser_on) {
      ++a;
      continue;
    }
    std::size_t b = a;
    while (b < n && c[b].laser_on) ++b;
    for (std::size_t k = a + static_cast<std::size_t>(on); k < std::min(n, b + static_cast<std::size_t>(off)); ++k) lit[k] = true;
    a = b;
  }
  for (std::size_t k = 0; k < n; ++k) c[k].laser_on = lit[k];
  return c;
}

Twin make_twin(const kinematics::Robot& robot, std::uint64_t seed, bool loaded_servo) {
  Twin t{robot, {}, {}};
  simulation::TrueComplianceOptions truth;
  truth.seed = seed;
  t.truth = simulation::make_true_compliance(robot, truth);
  t.options.mass_scale = 0.90;
  t.options.plant.tip_damping_ratio = 2.0 * robot.tip_damping_ratio;
  t.options.cg_lever = simulation::make_cg_lever(robot);
  t.options.plant.servo_feels_load = loaded_servo;
  // Integrated at 80 kHz, its mark recorded at 20 kHz: at its default 20 kHz the plant rounds the plate's tight arcs
  // ~2 µm short of its converged mark (CalibrationLoop), a twin's error the identification would take for physics.
  t.options.plant.step_rate_hz = 80e3;
  t.options.mark_rate_hz = 20e3;
  return t;
}

double twin_error_m(const Twin& twin, const std::vector<compensation::JointCommand>& told) {
  const auto commands = lit_late(told, twin.on_delay_samples, twin.off_delay_samples);
  std::size_t next = 0;
  const simulation::JointSource source = [&]() -> std::optional<compensation::JointCommand> {
    if (next == commands.size()) return std::nullopt;
    return commands[next++];
  };
  double worst = 0;
  (void)simulation::simulate(source, twin.robot, twin.truth, twin.options,
                             [&](const simulation::Stroke& s) { worst = std::max(worst, test::max_path_error_m(s)); });
  return worst;
}

// The truth's deflection per unit acceleration as the plant shows it: its mass over the file's times C_true (+ the
// CG lever), in the file's mass units.
compliance::Mat2 true_mc(const Twin& twin, const Vec2& p) {
  compliance::Mat2 c = twin.truth->compliance(p);
  if (twin.options.cg_lever) c += twin.options.cg_lever->compliance(p);
  return twin.options.mass_scale * c;
}

// An oracle for what a plate could at best find: the correction of the plate's family (S linear over the plate's
// area, S·C·S) fitted straight to the truth on a 9 × 9 grid over that area, every component of m·C weighed alike.
compliance::ComplianceCorrection best_correction(const Twin& twin, const compliance::Model& file,
                                                 const compliance::GridBounds& area) {
  compliance::ComplianceCorrection c;
  c.origin_m = {0.5 * (area.x_min + area.x_max), 0.5 * (area.y_min + area.y_max)};
  c.half_size_m = {0.5 * (area.x_max - area.x_min), 0.5 * (area.y_max - area.y_min)};
  const auto with = [c](const Eigen::VectorXd& x) {
    compliance::ComplianceCorrection out = c;
    out.sx = {x[0], x[1], x[2]}, out.sy = {x[3], x[4], x[5]}, out.sxy = {x[6], x[7], x[8]};
    return out;
  };
  core::LeastSquaresProblem problem;
  problem.residuals = [&](const Eigen::VectorXd& x) {
    const compliance::ComplianceCorrection k = with(x);
    Eigen::VectorXd r(81 * 4);
    int i = 0;
    for (int a = 0; a < 9; ++a) {
      for (int b = 0; b < 9; ++b) {
        const Vec2 p = c.origin_m + Vec2((-1 + 0.25 * a) * c.half_size_m.x(), (-1 + 0.25 * b) * c.half_size_m.y());
        const compliance::Mat2 C = file.compliance(p), S = k.matrix(p);
        const compliance::Mat2 miss = S * C * S - true_mc(twin, p);
        const double size = C.norm();
        for (int e = 0; e < 4; ++e) r[i++] = miss(e / 2, e % 2) / size;
      }
    }
    return r;
  };
  problem.scale = Eigen::VectorXd::Constant(9, 0.05);
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(9);
  x0[0] = x0[3] = 1.0;
  core::LevenbergMarquardt solver(problem, x0, {});
  solver.run();
  return with(solver.result(false).x);
}

struct ProofRow {
  std::uint64_t seed = 0;
  bool loaded_servo = true;
  double registration_um = 0, fit_s = 0, rms_before_um = 0, rms_after_um = 0;
  double mc_x_min = 0, mc_x_max = 0, mc_y_min = 0, mc_y_max = 0;  // identified m·C over true m·C at the stations
  double best_x_min = 0, best_x_max = 0, best_y_min = 0, best_y_max = 0;  // the same for best_correction
  double family_x_min = 0, family_x_max = 0, family_y_min = 0, family_y_max = 0;  // identified over best_correction
  double damping = 0, true_damping = 0;
  double on_delay_ms = 0, off_delay_ms = 0, true_on_delay_ms = 0, true_off_delay_ms = 0;
  struct Job {
    std::string name;
    double without_um, uncalibrated_um, calibrated_um, reference_um;
    double cycle_uncalibrated_s, cycle_calibrated_s;
  };
  std::vector<Job> jobs;
};

// One round on a twin of truth seed `seed`: the plate run by the uncalibrated default job and marked by the twin,
// drawn as a scan of a sheet turned and shifted on the bed at `dpi`, `calibrate fit` through the command line, then
// every held-out job run four ways and marked by the same twin. `loaded_servo`: the twin's drives feel the tip
// (its default), or track as if unloaded (the tip's error alone, which is what the calibration models).
ProofRow one_round(std::uint64_t seed, double dpi, bool loaded_servo = true) {
  ProofRow row;
  row.seed = seed;
  row.loaded_servo = loaded_servo;
  const auto robot = kinematics::load_robot("oc-gu");
  const Twin twin = make_twin(robot, seed, loaded_servo);
  const auto region = calibration::plate_region(robot);
  const calibration::PlateDesign plate = calibration::design_plate(robot, region);
  const job::JobSpec uncalibrated = job::default_job(robot);
  const auto plate_commands = test::commands_of(uncalibrated, calibration::plate_gcode(plate), "plate.gcode");

  std::vector<calibration::ObservedMark> marked;
  {
    const auto lit = lit_late(plate_commands, twin.on_delay_samples, twin.off_delay_samples);
    std::size_t next = 0;
    const simulation::JointSource source = [&]() -> std::optional<compensation::JointCommand> {
      if (next == lit.size()) return std::nullopt;
      return lit[next++];
    };
    // Each mark to the plate's stroke whose path its first commanded point lies on (the fiducials' are drawn apart).
    (void)simulation::simulate(source, robot, twin.truth, twin.options, [&](const simulation::Stroke& s) {
      if (s.commanded.empty()) return;
      for (const auto& stroke : plate.strokes) {
        const double nearest = evaluation::polyline_distance(s.commanded.front(), stroke.polyline_m());
        if (nearest < 5e-6 && (s.commanded.front() - stroke.start_m).norm() < 2e-3) marked.push_back({stroke.id, s.marked});
      }
    });
  }
  EXPECT_EQ(marked.size(), plate.strokes.size());
  Plate page = calibration_render_plate(plate, marked);
  ScannerBed bed;
  bed.width_m = page.width_m + 16e-3;
  bed.height_m = page.height_m + 16e-3;
  bed.page_at_m = {7e-3 + 0.3e-3 * static_cast<double>(seed), 4e-3};
  bed.page_angle_rad = (0.6 + 0.35 * static_cast<double>(seed)) * std::numbers::pi / 180.0;
  page.bed = bed;
  RenderOptions scanner;
  scanner.dpi = dpi;
  scanner.seed = static_cast<unsigned>(seed);

  test::TempDir dir;
  core::write_file_atomically(dir.path() / "plate.json", calibration::plate_json(plate));
  write_image(dir.path() / "scan.png", render_plate(page, scanner).image, dpi);
  {
    auto writer = job::make_joint_writer(job::OutputFormat::binary, (dir.path() / "joints.bin").string(), 2000.0,
                                         {robot.name, robot.geometry_hash()});
    for (const auto& c : plate_commands) writer->write(c);
    writer->finish();
  }
  const auto t0 = std::chrono::steady_clock::now();
  const test::CliResult fit = test::run_cli(
      "calibrate fit plate.json scan.png --joints joints.bin --robot oc-gu -o oc-gu-cal.json --json", dir.path());
  row.fit_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (fit.exit_code != 0) {
    ADD_FAILURE() << fit.err;
    return row;
  }
  const auto report = fit.json();
  row.registration_um = report["registration"]["residual_rms_um"].get<double>();
  row.rms_before_um = report["rms_before_um"].get<double>();
  row.rms_after_um = report["rms_after_um"].get<double>();
  // The truth's m·C at each station against what the plate found, and against the best its correction can do.
  const auto base = compliance::load_robot_model(robot);
  const compliance::ComplianceCorrection best = best_correction(twin, *base.model, plate.area);
  row.mc_x_min = row.mc_y_min = row.best_x_min = row.best_y_min = 1e9;
  row.mc_x_max = row.mc_y_max = row.best_x_max = row.best_y_max = -1e9;
  row.family_x_min = row.family_y_min = 1e9;
  row.family_x_max = row.family_y_max = -1e9;
  for (const auto& s : report["scales"]) {
    const Vec2 p(s["point_mm"][0].get<double>() * 1e-3, s["point_mm"][1].get<double>() * 1e-3);
    const compliance::Mat2 t = true_mc(twin, p), c = base.model->compliance(p), S = best.matrix(p);
    const compliance::Mat2 b = S * c * S;
    const double tx = t(0, 0) / c(0, 0), ty = t(1, 1) / c(1, 1);
    const double rx = s["scale"][0].get<double>() / tx, ry = s["scale"][1].get<double>() / ty;
    const double bx = b(0, 0) / t(0, 0), by = b(1, 1) / t(1, 1);
    std::printf("  station (%.1f, %.1f) mm: m*C over the file's: identified x %.4f, y %.4f; true x %.4f, y %.4f; "
                "best linear correction x %.4f, y %.4f\n",
                p.x() * 1e3, p.y() * 1e3, s["scale"][0].get<double>(), s["scale"][1].get<double>(), tx, ty,
                b(0, 0) / c(0, 0), b(1, 1) / c(1, 1));
    row.mc_x_min = std::min(row.mc_x_min, rx), row.mc_x_max = std::max(row.mc_x_max, rx);
    row.mc_y_min = std::min(row.mc_y_min, ry), row.mc_y_max = std::max(row.mc_y_max, ry);
    row.best_x_min = std::min(row.best_x_min, bx), row.best_x_max = std::max(row.best_x_max, bx);
    row.best_y_min = std::min(row.best_y_min, by), row.best_y_max = std::max(row.best_y_max, by);
    const double fx = s["scale"][0].get<double>() / (b(0, 0) / c(0, 0)), fy = s["scale"][1].get<double>() / (b(1, 1) / c(1, 1));
    row.family_x_min = std::min(row.family_x_min, fx), row.family_x_max = std::max(row.family_x_max, fx);
    row.family_y_min = std::min(row.family_y_min, fy), row.family_y_max = std::max(row.family_y_max, fy);
  }
  const kinematics::Robot calibrated_robot = kinematics::load_robot((dir.path() / "oc-gu-cal.json").string());
  row.damping = calibrated_robot.tip_damping_ratio;
  row.on_delay_ms = calibrated_robot.laser_on_delay_s * 1e3;
  row.off_delay_ms = calibrated_robot.laser_off_delay_s * 1e3;
  row.true_on_delay_ms = twin.on_delay_s() * 1e3;
  row.true_off_delay_ms = twin.off_delay_s() * 1e3;
  row.true_damping = *twin.options.plant.tip_damping_ratio;

  // The reference: the same default compensation told the truth's mass and damping, with a model fitted to a CMM
  // campaign of the twin (noisy readings at the robot's own measurement points).
  kinematics::Robot told = robot;
  told.moving_mass_kg = robot.moving_mass_kg * twin.options.mass_scale;
  told.tip_damping_ratio = row.true_damping;
  job::JobSpec reference = job::default_job(told);
  reference.model.given = simulation::fit_compensation_model(*twin.truth, robot);
  const job::JobSpec calibrated = job::default_job(calibrated_robot);
  job::JobSpec without = job::default_job(robot);
  without.compensate = false;

  for (const auto& job : test::held_out_jobs(region)) {
    const auto u = test::commands_of(uncalibrated, job.gcode, job.name + ".gcode");
    const auto c = test::commands_of(calibrated, job.gcode, job.name + ".gcode");
    row.jobs.push_back({job.name, twin_error_m(twin, test::commands_of(without, job.gcode, job.name + ".gcode")) * 1e6,
                        twin_error_m(twin, u) * 1e6, twin_error_m(twin, c) * 1e6,
                        twin_error_m(twin, test::commands_of(reference, job.gcode, job.name + ".gcode")) * 1e6,
                        u.back().t_s - u.front().t_s, c.back().t_s - c.front().t_s});
  }
  return row;
}

void print(const ProofRow& r) {
  std::printf("seed %llu, %s servo: registration %.2f um rms, calibrate fit %.1f s, misfit %.1f -> %.1f um rms; "
              "m*C at the stations, identified / true: x %.3f-%.3f, y %.3f-%.3f; identified / best linear correction: "
              "x %.3f-%.3f, y %.3f-%.3f; best / true: x %.3f-%.3f, y %.3f-%.3f; damping %.4f (true %.4f); laser delays on "
              "%.3f ms, off %.3f ms (true %.3f, %.3f)\n",
              static_cast<unsigned long long>(r.seed), r.loaded_servo ? "loaded" : "ideal", r.registration_um, r.fit_s,
              r.rms_before_um, r.rms_after_um, r.mc_x_min, r.mc_x_max, r.mc_y_min, r.mc_y_max, r.family_x_min,
              r.family_x_max, r.family_y_min, r.family_y_max, r.best_x_min, r.best_x_max, r.best_y_min, r.best_y_max,
              r.damping, r.true_damping, r.on_delay_ms, r.off_delay_ms, r.true_on_delay_ms, r.true_off_delay_ms);
  std::printf("  %-9s %10s %13s %11s %10s %8s %10s  (max path error)\n", "job", "without", "uncalibrated", "calibrated",
              "reference", "cal/ref", "cal/uncal");
  for (const auto& j : r.jobs) {
    std::printf("  %-9s %7.1f um %10.1f um %8.1f um %7.1f um %8.2f %10.2f\n", j.name.c_str(), j.without_um,
                j.uncalibrated_um, j.calibrated_um, j.reference_um, j.calibrated_um / j.reference_um,
                j.calibrated_um / j.uncalibrated_um);
  }
  std::fflush(stdout);
}

// What one round achieves on this twin, asserted: the registration within 10 µm and the misfit at least halved; the
// laser's delays within 0.1 ms (the twin records its mark every 0.05 ms); m·C at the stations within 10 % of what the
// correction's own family can best do (best_correction); cycle times unchanged. With the drives loaded (the twin's
// default) every held-out job within 1.3× of the reference and the damping within 30 %; with them ideal, the median
// job's error at most half the uncalibrated default's. (The m·C within ±3 % of the truth and 50 % below the
// uncalibrated default on every job are printed, not met: docs/calibration.md, "What a plate cannot tell".)
void check(const ProofRow& r) {
  EXPECT_LE(r.registration_um, 10.0);
  EXPECT_LT(r.rms_after_um, 0.5 * r.rms_before_um);
  EXPECT_NEAR(r.on_delay_ms, r.true_on_delay_ms, 0.1);
  EXPECT_NEAR(r.off_delay_ms, r.true_off_delay_ms, 0.1);
  EXPECT_GE(std::min(r.family_x_min, r.family_y_min), 0.9);
  EXPECT_LE(std::max(r.family_x_max, r.family_y_max), 1.1);
  std::vector<double> gains;
  for (const auto& j : r.jobs) {
    if (r.loaded_servo) EXPECT_LE(j.calibrated_um, 1.3 * j.reference_um) << j.name;
    gains.push_back(j.calibrated_um / j.uncalibrated_um);
    EXPECT_NEAR(j.cycle_calibrated_s, j.cycle_uncalibrated_s, 1e-9) << j.name;
  }
  if (r.loaded_servo) {
    EXPECT_NEAR(r.damping, r.true_damping, 0.3 * r.true_damping);
  } else {
    std::nth_element(gains.begin(), gains.begin() + static_cast<std::ptrdiff_t>(gains.size() / 2), gains.end());
    EXPECT_LE(gains[gains.size() / 2], 0.5);
  }
}

// One truth seed, the scan at 600 dpi (the suite's budget; scripts/calibration_proof.sh runs five at 1200 dpi).
TEST(CalibrationProof, OneRoundOnATwinThatIsNotItsFile) {
  const ProofRow r = one_round(3, 600);
  print(r);
  check(r);
}

// The proof in full: five truth seeds, A4 at 1200 dpi, the twin's drives loaded and ideal (minutes: run by
// scripts/calibration_proof.sh).
TEST(CalibrationProof, DISABLED_FiveTruthSeedsAt1200Dpi) {
  for (const bool loaded : {true, false}) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      const ProofRow r = one_round(seed, 1200, loaded);
      print(r);
      check(r);
    }
  }
}

}  // namespace
}  // namespace stiffpath::vision
