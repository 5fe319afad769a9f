// Geometry calibration against a synthetic robot whose true geometry is known: recovery, uncertainty, identifiability, plans.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "cli_runner.hpp"
#include "stiffpath/calibration/geometry_fit.hpp"
#include "stiffpath/calibration/geometry_plan.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::calibration {
namespace {

using kinematics::Vec2;
constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kSigma = 11.5e-6;  // the arm's ±23 µm as 2σ

kinematics::Robot asym() { return kinematics::load_robot(STIFFPATH_SOURCE_DIR "/examples/robots/asym_5bar.json"); }

// The robot file's geometry moved by the tolerances: links ±0.3 mm, actuators ±0.2 mm, zeros ±0.1°.
kinematics::FiveBarGeometry perturbed(const kinematics::FiveBarGeometry& g, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  kinematics::FiveBarGeometry t = g;
  for (int i = 0; i < 2; ++i) {
    t.actuator_m[i] += 0.2e-3 * Vec2(u(rng), u(rng));
    t.proximal_m[i] += 0.3e-3 * u(rng);
    t.distal_m[i] += 0.3e-3 * u(rng);
    t.joint_zero_rad[i] += 0.1 * kDeg * u(rng);
  }
  return t;
}

// An instrument standing somewhere: turned by `yaw` about z (and tilted when spatial), shifted.
InstrumentFrame frame(double yaw, bool spatial) {
  InstrumentFrame f;
  f.rotation = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(spatial ? 0.3 : 0.0, Eigen::Vector3d(1, 1, 0).normalized()))
                   .toRotationMatrix();
  f.translation_m = Eigen::Vector3d(0.812, -1.234, spatial ? 0.457 : 0.0);
  return f;
}

// The truth seen in the fit's gauge: the robot moved rigidly so that the held parameters (left actuator, θ1's
// zero) have the robot file's values, and the instrument frame moved the other way: the same readings.
Eigen::VectorXd truth_in_gauge(const GeometryModel& model, const kinematics::FiveBarGeometry& truth,
                               const InstrumentFrame& f) {
  const auto& nominal = model.nominal().geometry;
  const double e = nominal.joint_zero_rad[0] - truth.joint_zero_rad[0];
  const Eigen::Rotation2Dd R(e);
  const Vec2 d = nominal.actuator_m[0] - R * truth.actuator_m[0];
  kinematics::FiveBarGeometry g = truth;
  for (int i = 0; i < 2; ++i) {
    g.actuator_m[i] = R * truth.actuator_m[i] + d;
    g.joint_zero_rad[i] = truth.joint_zero_rad[i] + e;
  }
  InstrumentFrame moved;
  const Eigen::Matrix3d R3 = Eigen::AngleAxisd(e, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  moved.rotation = f.rotation * R3.transpose();
  moved.translation_m = f.translation_m - moved.rotation * Eigen::Vector3d(d.x(), d.y(), 0.0);
  return model.pack(g, moved);
}

// Random reachable poses of the robot file (held-out poses).
std::vector<Vec2> random_poses(const kinematics::Robot& robot, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(-0.3, 0.3), y(-0.1, 0.35);
  std::vector<Vec2> q;
  while (static_cast<int>(q.size()) < count) {
    const Vec2 p(x(rng), y(rng));
    if (robot.refusal(p).empty()) q.push_back(robot.inverse(p));
  }
  return q;
}

// The 30-pose plans of the two robots, made once (a plan takes a few hundred ms).
const GeometryPlan& plan_of(const kinematics::Robot& robot) {
  static std::map<std::string, GeometryPlan> plans;
  const auto it = plans.find(robot.name);
  if (it != plans.end()) return it->second;
  GeometryPlanSettings ps;
  ps.poses = 30;
  return plans.emplace(robot.name, plan_geometry_poses(robot, ps)).first->second;
}

std::vector<Vec2> angles(const GeometryPlan& plan) {
  std::vector<Vec2> q;
  for (const auto& p : plan.poses) q.push_back(p.q_rad);
  return q;
}

TEST(GeometryFit, ExactReadingsGiveTheTrueGeometryInTheFitsGauge) {
  const auto robot = asym();
  const auto truth = perturbed(robot.geometry, 1);
  const InstrumentFrame f = frame(0.7, false);
  const GeometryPlan& plan = plan_of(robot);
  GeometryRehearsal rehearsal{f, 0.0, 1, false, 1};
  const GeometryReadings readings = simulate_geometry_readings(truth, angles(plan), rehearsal);
  const GeometryFitResult fit = fit_geometry(robot, readings);
  const GeometryModel model(robot, fit.start_rotation);
  const Eigen::VectorXd want = truth_in_gauge(model, truth, f);
  for (int k = 0; k < kGeometryParameters; ++k) {
    if (!fit.parameters[static_cast<std::size_t>(k)].applicable) continue;
    EXPECT_NEAR(fit.x(k), want(k), k == 8 || k == 9 || (k >= 10 && k <= 12) ? 1e-8 : 1e-8) << parameter_name(k);
  }
  EXPECT_LT(fit.rms_after_m, 1e-9);
  EXPECT_GT(fit.rms_before_m, 20e-6);  // the tolerances move the tool point by far more than the arm's noise
  // Held: the three directions of the robot's place in the instrument's frame, and nothing else.
  std::vector<std::string> held;
  for (const auto& p : fit.parameters) {
    if (p.fixed) held.push_back(p.name);
  }
  EXPECT_EQ(held, (std::vector<std::string>{"left_actuator_x_mm", "left_actuator_y_mm", "theta1_zero_deg"}));
  EXPECT_EQ(fit.undetermined.size(), 3u);
  EXPECT_FALSE(fit.mirrored);
}

// The target: ≤ 40 planned poses, the arm's noise, a rotated and shifted instrument (planar and 3-D):
// held-out tool points within 1.5× the noise, and every identifiable parameter within 3σ of the truth.
TEST(GeometryFit, PlannedPosesWithTheArmsNoiseMeetTheTargets) {
  for (const char* name : {"asym", "oc-gu"}) {
    const auto robot = std::string(name) == "asym" ? asym() : kinematics::load_robot(name);
    const GeometryPlan& plan = plan_of(robot);
    const std::vector<Vec2> held_out = random_poses(robot, 50, 99);
    int checks = 0, outside_3sigma = 0;
    double worst_z = 0.0, sum_z2 = 0.0;
    for (const bool spatial : {false, true}) {
      for (unsigned seed = 1; seed <= 4; ++seed) {
        const auto truth = perturbed(robot.geometry, seed * 17);
        const InstrumentFrame f = frame(0.3 * seed, spatial);
        GeometryRehearsal rehearsal{f, kSigma, 1, spatial, seed + (spatial ? 100u : 0u)};
        const GeometryFitResult fit = fit_geometry(robot, simulate_geometry_readings(truth, angles(plan), rehearsal));
        ASSERT_EQ(fit.parameters.size(), static_cast<std::size_t>(kGeometryParameters));
        const GeometryModel model(robot, fit.start_rotation);
        const Eigen::VectorXd want = truth_in_gauge(model, truth, f);
        for (int k = 0; k < kGeometryParameters; ++k) {
          const auto& p = fit.parameters[static_cast<std::size_t>(k)];
          if (p.fixed || !p.applicable) continue;
          const double z = std::abs(fit.x(k) - want(k)) / p.sigma;
          worst_z = std::max(worst_z, z);
          ++checks;
          outside_3sigma += z > 3.0 ? 1 : 0;
          sum_z2 += z * z;
        }
        // Held-out poses: the fitted model's prediction against the truth and against fresh noisy readings.
        GeometryRehearsal fresh{f, kSigma, 1, spatial, seed + 1000};
        const GeometryReadings test = simulate_geometry_readings(truth, held_out, fresh);
        double sum_truth = 0.0, sum_reading = 0.0;
        const int dims = spatial ? 3 : 2;
        for (std::size_t i = 0; i < held_out.size(); ++i) {
          const Eigen::Vector3d predicted = model.reading(fit.x, held_out[i]);
          const Eigen::Vector3d exact = f.to_instrument(GeometryModel::end_point(truth, held_out[i]));
          sum_truth += (predicted - exact).head(dims).squaredNorm();
          sum_reading += (predicted - test.rows[i].point_m).head(dims).squaredNorm();
        }
        const double n = static_cast<double>(held_out.size() * static_cast<std::size_t>(dims));
        const double rms_truth = std::sqrt(sum_truth / n), rms_reading = std::sqrt(sum_reading / n);
        std::printf("%s %s seed %u: before %.1f um rms, after %.1f um; held-out rms vs truth %.1f um, vs readings %.1f um\n",
                    name, spatial ? "3-D" : "planar", seed, fit.rms_before_m * 1e6, fit.rms_after_m * 1e6,
                    rms_truth * 1e6, rms_reading * 1e6);
        EXPECT_LT(rms_reading, 1.5 * kSigma) << name << " seed " << seed;
        EXPECT_LT(rms_truth, kSigma) << name << " seed " << seed;
      }
    }
    const double rms_z = std::sqrt(sum_z2 / checks);
    std::printf("%s: %d of %d identifiable parameters outside 3 sigma (largest |error|/sigma %.2f, rms %.2f)\n", name,
                outside_3sigma, checks, worst_z, rms_z);
    // 3σ holds 99.7 % of a normal error (σ estimated from 47 degrees of freedom: 99.6 %); over 300 seeds of the
    // planar case 13 of 3000 fell outside (0.4 %), with |error|/σ of RMS 0.94–1.11 per parameter. Of these
    // ~90, at most 2 may fall outside, and the errors' RMS in units of their σ must be about 1.
    EXPECT_LE(outside_3sigma, 2) << name;
    EXPECT_GT(rms_z, 0.75) << name;
    EXPECT_LT(rms_z, 1.3) << name;
  }
}

TEST(GeometryFit, StatedUncertaintiesMatchTheSpreadOfRepeatedCalibrations) {
  // The same robot measured 40 times with fresh noise: the stated σ of each fitted parameter against the
  // standard deviation of its estimates (a χ² oracle for the covariance, independent of the fit's own numbers).
  const auto robot = asym();
  const auto q = angles(plan_of(robot));
  const auto truth = perturbed(robot.geometry, 5);
  const InstrumentFrame f = frame(1.1, false);
  constexpr int kRuns = 40;
  Eigen::MatrixXd estimates(kRuns, kGeometryParameters);
  Eigen::VectorXd stated = Eigen::VectorXd::Zero(kGeometryParameters);
  std::vector<bool> fitted(kGeometryParameters, false);
  for (int run = 0; run < kRuns; ++run) {
    GeometryRehearsal rehearsal{f, kSigma, 1, false, static_cast<std::uint64_t>(run + 1)};
    const auto fit = fit_geometry(robot, simulate_geometry_readings(truth, q, rehearsal));
    estimates.row(run) = fit.x.transpose();
    for (int k = 0; k < kGeometryParameters; ++k) {
      stated(k) += fit.parameters[static_cast<std::size_t>(k)].sigma / kRuns;
      fitted[static_cast<std::size_t>(k)] = !fit.parameters[static_cast<std::size_t>(k)].fixed && fit.parameters[static_cast<std::size_t>(k)].applicable;
    }
  }
  for (int k = 0; k < kGeometryParameters; ++k) {
    if (!fitted[static_cast<std::size_t>(k)]) continue;
    const Eigen::VectorXd col = estimates.col(k);
    const double sd = std::sqrt((col.array() - col.mean()).square().sum() / (kRuns - 1));
    // 40 runs: the sample σ is within ±25 % of the true σ with about 95 % probability.
    EXPECT_GT(sd / stated(k), 0.7) << parameter_name(k);
    EXPECT_LT(sd / stated(k), 1.35) << parameter_name(k);
  }
}

TEST(GeometryFit, MirroredPlanarReadingsAreRecognised) {
  const auto robot = asym();
  const auto truth = perturbed(robot.geometry, 3);
  InstrumentFrame f = frame(-0.4, false);
  f.rotation = f.rotation * Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();  // the plane seen from below
  const auto fit = fit_geometry(robot, simulate_geometry_readings(truth, angles(plan_of(robot)), {f, kSigma, 1, false, 4}));
  EXPECT_TRUE(fit.mirrored);
  EXPECT_LT(fit.rms_after_m, 1.3 * kSigma);
}

TEST(GeometryFit, PosesCrowdedInOneCornerLeaveMoreUndeterminedAndSaySo) {
  const auto robot = asym();
  GeometryPlanSettings ps;
  ps.poses = 12;
  ps.region = compliance::GridBounds{-0.01, 0.01, 0.20, 0.22};
  ps.min_separation_fraction = 0.0;
  const auto truth = perturbed(robot.geometry, 8);
  const auto fit = fit_geometry(robot, simulate_geometry_readings(truth, angles(plan_geometry_poses(robot, ps)),
                                                                  {frame(0.2, false), kSigma, 1, false, 2}));
  int held = 0;
  for (const auto& p : fit.parameters) held += p.fixed ? 1 : 0;
  EXPECT_GT(held, 3);
  EXPECT_EQ(fit.undetermined.size(), static_cast<std::size_t>(held));
  for (const auto& d : fit.undetermined) EXPECT_FALSE(d.shares.empty());
  EXPECT_LT(fit.rms_after_m, 1.5 * kSigma);  // what it cannot separate, it does not need to fit these readings
}

TEST(GeometryFit, APoseTheRobotFileCannotCloseIsRefusedWithItsLine) {
  const auto robot = asym();
  GeometryReadings r{"r.csv", false, {}};
  GeometryReading bad;
  bad.line = 7;
  // The elbows meet where the proximal links' circles cross, (−15.625, 117.5) mm: the distal links (180 and
  // 170 mm) cannot close a loop on a point.
  bad.q_rad = Vec2(std::atan2(117.5, 24.375), std::atan2(117.5, -55.625));
  r.rows.push_back(bad);
  try {
    (void)fit_geometry(robot, r);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where().line, 7);
    EXPECT_NE(std::string(e.what()).find("cannot meet"), std::string::npos) << e.what();
  }
}

TEST(GeometryPlan, PosesAreReachableSpreadAndBetterThanAGridOfAsMany) {
  const auto robot = asym();
  // A regular 7 × 7 lattice over the reachable region's bounding box, kept where the robot reaches.
  const GeometryPlan& wide = plan_of(robot);
  auto b = compliance::GridBounds::none();
  for (const auto& p : wide.reachable) b.include(p);
  std::vector<Vec2> grid;
  for (int i = 0; i < 7; ++i) {
    for (int j = 0; j < 7; ++j) {
      const Vec2 p(b.x_min + (b.x_max - b.x_min) * i / 6.0, b.y_min + (b.y_max - b.y_min) * j / 6.0);
      if (robot.refusal(p).empty()) grid.push_back(robot.inverse(p));
    }
  }
  ASSERT_GE(grid.size(), 10u);
  GeometryPlanSettings ps;
  ps.poses = static_cast<int>(grid.size());
  const GeometryPlan plan = plan_geometry_poses(robot, ps);
  ASSERT_EQ(plan.poses.size(), grid.size());
  for (std::size_t i = 0; i < plan.poses.size(); ++i) {
    const auto& p = plan.poses[i];
    EXPECT_TRUE(robot.refusal(p.p_m).empty());
    EXPECT_TRUE(robot.within_limits(p.q_rad));
    EXPECT_LT((robot.five_bar().forward(p.q_rad) - p.p_m).norm(), 1e-12);
    for (std::size_t j = 0; j < i; ++j) EXPECT_GE((p.p_m - plan.poses[j].p_m).norm(), plan.min_separation_m * (1 - 1e-12));
  }
  EXPECT_EQ(plan.held, (std::vector<std::string>{"left_actuator_x_mm", "left_actuator_y_mm", "theta1_zero_deg"}));
  const double grid_log_det = geometry_log_det(robot, grid, ps);
  std::printf("log det of the scaled information, %zu poses: plan %.2f, grid %.2f\n", grid.size(), plan.log_det, grid_log_det);
  EXPECT_NEAR(geometry_log_det(robot, angles(plan), ps), plan.log_det, 1e-3);  // the plan's number is the criterion's
  EXPECT_GT(plan.log_det, grid_log_det + 1.0);  // e¹ more volume at least: each σ about 10 % smaller on average
  for (int k = 0; k < kRobotParameters; ++k) {
    const double s = plan.predicted_sigma[static_cast<std::size_t>(k)];
    if (k == 0 || k == 1 || k == 8) {
      EXPECT_EQ(s, 0.0);
    } else {
      EXPECT_GT(s, 0.0);
      EXPECT_LT(s, k < 8 ? 0.2e-3 : 0.1 * kDeg);  // better than the parts' tolerances
    }
  }
}

TEST(GeometryReadingsFile, RoundTripAndLocatedErrors) {
  test::TempDir dir;
  GeometryReadings r{"x", true, {}};
  GeometryReading a;
  a.q_rad = Vec2(1.0, -0.5);
  a.point_m = Eigen::Vector3d(0.1, 0.2, -0.3);
  r.rows = {a, a};
  r.rows[1].reading = 2;
  save_geometry_readings(r, (dir / "r.csv").string());
  const auto back = load_geometry_readings((dir / "r.csv").string());
  ASSERT_EQ(back.rows.size(), 2u);
  EXPECT_TRUE(back.has_z);
  EXPECT_NEAR(back.rows[1].q_rad.x(), 1.0, 1e-10);
  EXPECT_NEAR(back.rows[1].point_m.z(), -0.3, 1e-9);
  EXPECT_EQ(back.rows[1].reading, 2);
  EXPECT_EQ(back.rows[1].line, 3);
  const auto error_of = [&](const std::string& text) {
    test::write_text(dir / "bad.csv", text);
    try {
      (void)load_geometry_readings((dir / "bad.csv").string());
    } catch (const Error& e) {
      return std::string(e.what()).substr((dir / "bad.csv").string().size());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of("theta1_deg,theta2_deg,x_mm\n1,2,3\n"),
            ":1:1: missing column 'y_mm' (a readings file has the columns theta1_deg,theta2_deg,x_mm,y_mm[,z_mm][,reading])");
  EXPECT_EQ(error_of("theta1_deg,theta2_deg,x_m,y_mm\n1,2,3,4\n"), ":1:23: column 'x_m': unit 'm' is not supported, give x_mm");
  EXPECT_EQ(error_of("theta1_deg,theta2_deg,x_mm,y_mm\n1,2,3,4\n900,2,3,4\n"),
            ":3:1: column 'theta1_deg': 900 is beyond +-540 deg");
  EXPECT_EQ(error_of("theta1_deg,theta2_deg,x_mm,y_mm\n1,2,3,4\n1,2,3,nan\n"),
            ":3:7: column 'y_mm': 'nan' is not a finite number");
  EXPECT_EQ(error_of("theta1_deg,theta2_deg,x_mm,y_mm\n1,2,3,4\n1,2,3.1,4\n"),
            ":3:1: pose (theta1 = 1 deg, theta2 = 2 deg) reading 1 was already given on line 2 (number repeated "
            "readings in a 'reading' column)");
  EXPECT_EQ(error_of("theta1_deg,theta2_deg,x_mm,y_mm\n"), ":1:1: the readings file has no readings");
}

}  // namespace
}  // namespace stiffpath::calibration
