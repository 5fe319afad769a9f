// Tests of compliance models for a general robot: the statics' force split, the virtual joint method, geometry checks, old files.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <random>

#include "cli_runner.hpp"
#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/compliance/physical_model.hpp"
#include "stiffpath/core/error.hpp"
#include "synthetic_table.hpp"

namespace stiffpath::compliance {
namespace {

kinematics::FiveBarGeometry asymmetric() {
  kinematics::FiveBarGeometry g;
  g.actuator_m = {Vec2(-0.04, 0.0), Vec2(0.04, 0.0)};
  g.proximal_m = {0.120, 0.130};
  g.distal_m = {0.180, 0.170};
  return g;
}

// The distal unit vectors by circle intersection, written independently of the library.
std::array<Vec2, 2> distal_directions(const kinematics::FiveBarGeometry& g, const Vec2& c) {
  std::array<Vec2, 2> u;
  for (int i = 0; i < 2; ++i) {
    const Vec2 d = c - g.actuator_m[i];
    const double D = d.norm(), lp = g.proximal_m[i], ld = g.distal_m[i];
    const double a = std::acos((D * D + lp * lp - ld * ld) / (2 * D * lp));
    const double theta = std::atan2(d.y(), d.x()) + g.elbows[i] * a;
    const Vec2 b = g.actuator_m[i] + lp * Vec2(std::cos(theta), std::sin(theta));
    u[i] = (c - b) / ld;
  }
  return u;
}

TEST(GeneralStatics, TheLinkForcesAddUpToTheAppliedForce) {
  const auto g = asymmetric();
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> ux(-0.06, 0.06), uy(0.17, 0.25), uf(-300, 300);
  for (int k = 0; k < 500; ++k) {
    const Vec2 c{ux(rng), uy(rng)}, F{uf(rng), uf(rng)};
    const auto u = distal_directions(g, c);
    const Vec2 f = PhysicalModel::link_force_map(g, c) * F;
    ASSERT_LT((f.x() * u[0] + f.y() * u[1] - F).norm(), 1e-10 * (1 + F.norm()));
  }
}

TEST(GeneralStatics, ActuatorComplianceEqualsTheVirtualJointMethod) {
  // Only the actuators compliant (κ_i rad/(N·m)): δp = J diag(κ) Jᵀ F. Through the link forces, the
  // torque of link force f_i is f_i·l_pi (e_i⊥·u_i), so D = diag(κ_i (l_pi e_i⊥·u_i)²).
  const auto g = asymmetric();
  const kinematics::FiveBar robot(g, {});
  const double k1 = 2e-4, k2 = 3e-4;
  for (const Vec2& c : {Vec2(-0.05, 0.18), Vec2(0.0, 0.21), Vec2(0.045, 0.245)}) {
    kinematics::InverseFrame frame;
    ASSERT_EQ(robot.solve_inverse(c, frame).status, kinematics::Reach::ok);
    const Mat2 vjm = frame.jacobian * Vec2(k1, k2).asDiagonal() * frame.jacobian.transpose();
    Vec2 lever;
    for (int i = 0; i < 2; ++i) {
      const Vec2 e = frame.proximal[static_cast<std::size_t>(i)], u = frame.distal[static_cast<std::size_t>(i)];
      lever[i] = g.proximal_m[static_cast<std::size_t>(i)] * (-e.y() * u.x() + e.x() * u.y());
    }
    const Mat2 D = Vec2(k1 * lever.x() * lever.x(), k2 * lever.y() * lever.y()).asDiagonal();
    const Mat2 Ui = PhysicalModel::link_force_map(g, c);
    EXPECT_LT((Ui.transpose() * D * Ui - vjm).norm(), 1e-12 * vjm.norm()) << c.transpose();
  }
}

TEST(RobotModels, AModelKnowsItsGeometryAndIsRefusedForAnother) {
  const auto thesis = kinematics::load_robot("oc-gu");
  kinematics::Robot mine = thesis;
  mine.name = "mine";
  mine.geometry = asymmetric();
  const LoadedModel m = load_model("thesis-oc");
  EXPECT_NO_THROW(check_model_geometry(m, kinematics::load_robot("sc-gl"), false));  // same five-bar
  try {
    check_model_geometry(m, mine, false);
    FAIL();
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("model thesis-oc was fitted for robot 'oc-gu' (geometry " +
                             kinematics::geometry_hash(thesis.geometry).substr(0, 12) + "), not for robot 'mine' (geometry " +
                             kinematics::geometry_hash(mine.geometry).substr(0, 12) + ")",
                         0),
              0U)
        << what;
  }
  EXPECT_NO_THROW(check_model_geometry(m, mine, true));
  // A format-1 file records no geometry: refused unless forced.
  LoadedModel old = load_model("thesis-oc");
  old.provenance.geometry.reset();
  EXPECT_THROW(check_model_geometry(old, thesis, false), Error);
  EXPECT_NO_THROW(check_model_geometry(old, thesis, true));
}

TEST(RobotModels, FormatOneFilesStillLoad) {
  // A physical model file as version 1 wrote it: the thesis robot's link length, no robot block.
  const auto fitted = fit_model(measurement::load_displacement_table(measurement::thesis_dataset()), "OC", FitMethod::physical,
                                ForceConvention::measured, kinematics::load_robot("oc-gu"));
  nlohmann::json doc = model_to_json(*fitted.model, fitted.provenance);
  doc["version"] = 1;
  doc.erase("robot");
  doc.erase("geometry");
  doc["link_length_mm"] = 150.0;
  doc["provenance"].erase("rows");
  doc["provenance"]["mechanism"] = "OC";
  const LoadedModel back = model_from_json(core::parse_json_document(doc.dump(), "old.json"));
  EXPECT_FALSE(back.provenance.geometry.has_value());
  EXPECT_EQ(back.provenance.rows, "OC");
  for (const Vec2& p : {Vec2(0.2, 0.01), Vec2(0.26, -0.07)}) {
    EXPECT_LT((back.model->compliance(p) - fitted.model->compliance(p)).norm(), 1e-18);
  }
}

TEST(RobotModels, TheErrorPolicyRefusesBeyondTheMarginOnly) {
  const LoadedModel m = load_model("thesis-oc");
  ASSERT_EQ(m.model->outside_policy(), OutsidePolicy::error);
  EXPECT_FALSE(m.model->refuses({0.272132 + 0.0009, 0.0}));
  EXPECT_TRUE(m.model->refuses({0.272132 + 0.0011, 0.0}));
  EXPECT_TRUE(m.model->refuses({0.2, -0.0762}));
  m.model->set_outside_policy(OutsidePolicy::clamp);
  EXPECT_FALSE(m.model->refuses({0.5, 0.5}));
}

TEST(RobotModels, CrossValidationOnAnIrregularLayoutRunsThePhysicalModelsOnly) {
  // The thesis grid without x2y3: not a full grid.
  const auto truth = [](const Vec2& p) {
    Mat2 c;
    c << 1.0 + 3 * p.x(), 0.2, 0.2, 2.0 + 5 * p.y();
    return Mat2(c * 1e-6);
  };
  auto table = test::synthetic_table(truth, [](const Vec2&) { return Vec2::Zero(); });
  std::erase_if(table.rows, [](const measurement::DisplacementRow& r) { return r.point == "x2y3"; });
  const CvReport r = cross_validate(group_by_point(table, ForceConvention::measured),
                                    kinematics::FiveBarGeometry::thesis(0.15), table.source);
  ASSERT_EQ(r.skipped.size(), 2U);
  EXPECT_EQ(r.skipped[0].method, FitMethod::bilinear);
  EXPECT_EQ(r.skipped[1].method, FitMethod::symmetric);
  ASSERT_EQ(r.methods.size(), 4U);
  EXPECT_EQ(r.methods[0].method, FitMethod::physical_0);
  EXPECT_EQ(r.methods[3].method, FitMethod::physical_spline);
  EXPECT_EQ(r.methods[1].predicted, 14);
  int interior = 0;
  for (const auto& p : r.methods[1].points) interior += p.interior;
  EXPECT_EQ(interior, 2);  // x2y2 and x2y4: strictly inside the points' rectangle
  std::vector<std::pair<FitMethod, double>> scores;
  const FitMethod best = favoured_method(r, &scores);
  ASSERT_EQ(scores.size(), 4U);
  const auto smallest = std::min_element(scores.begin(), scores.end(),
                                         [](const auto& a, const auto& b) { return a.second < b.second; });
  EXPECT_EQ(best, smallest->first);
}

TEST(RobotModels, AutoPicksTheMethodCrossValidationFavoursAndRecordsWhy) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto table = measurement::load_displacement_table(robot.compliance.table);
  const LoadedModel m = fit_model(table, "OC", std::nullopt, ForceConvention::measured, robot);
  EXPECT_EQ(m.model->method(), FitMethod::physical_spline);  // 16.3 µm on the common points against 90.1 for bilinear
  EXPECT_EQ(m.provenance.selected_by, MethodSelection::cross_validation);
  EXPECT_NEAR(m.provenance.selection["mean_error_um"]["bilinear"].get<double>(), 90.07, 0.01);
  EXPECT_NEAR(m.provenance.selection["mean_error_um"]["physical"].get<double>(), 24.12, 0.01);
  EXPECT_LT(m.provenance.selection["mean_error_um"]["physical-spline"].get<double>(), 17.0);
  // The presets name no method: their own model is the one cross-validation favours, as for any robot.
  EXPECT_EQ(load_robot_model(robot).model->method(), FitMethod::physical_spline);
  // A method the robot file names wins over cross-validation, and one the request names over both.
  kinematics::Robot named = robot;
  named.compliance.method = FitMethod::bilinear;
  EXPECT_EQ(load_robot_model(named).model->method(), FitMethod::bilinear);
  ModelRequest physical;
  physical.method = FitMethod::physical;
  EXPECT_EQ(load_robot_model(named, physical).model->method(), FitMethod::physical);
}

}  // namespace
}  // namespace stiffpath::compliance
