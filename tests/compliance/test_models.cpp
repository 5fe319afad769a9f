// Tests of the symmetric and physical models, model files and cross-validation on known fields.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "cli_runner.hpp"
#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/compliance/physical_model.hpp"
#include "stiffpath/core/error.hpp"
#include "synthetic_table.hpp"

namespace stiffpath::compliance {
namespace {

constexpr double kL = 0.150;
const kinematics::FiveBarGeometry kThesis = kinematics::FiveBarGeometry::thesis(kL);
const GridBounds kGrid{0.172132, 0.272132, -0.075, 0.075};

// A physical model with known D coefficients (µm/N), order 1.
std::unique_ptr<PhysicalModel> known_physical() {
  return std::make_unique<PhysicalModel>(
      kThesis, kGrid, 1, std::vector<std::array<double, 3>>{{1.5e-6, 0.1e-6, 1.2e-6}, {0.3e-6, 0.0, -0.2e-6}, {0.0, 0.05e-6, 0.1e-6}},
      nlohmann::json::object());
}

TEST(PhysicalModel, LinkForceMapSplitsTheForceIntoTheDistalLinks) {
  // F = f_AC·w2 + f_BC·w1 must hold for f = U⁻¹F, with θ from an independent eq. 2.2.
  const Vec2 p{0.23, 0.04};
  const double r = p.norm(), phi = std::atan2(p.y(), p.x()), eta = std::acos(r / (2 * kL));
  const Vec2 w1{std::cos(phi + eta), std::sin(phi + eta)}, w2{std::cos(phi - eta), std::sin(phi - eta)};
  const Vec2 F{120.0, -75.0};
  const Vec2 f = PhysicalModel::link_force_map(kThesis, p) * F;
  EXPECT_LT((f.x() * w2 + f.y() * w1 - F).norm(), 1e-12);
}

TEST(PhysicalModel, ActuatorComplianceEqualsJacobianMapping) {
  // With D = diag(κ1, κ2)·l²·sin²(θ1 − θ2), U⁻ᵀDU⁻¹ = J diag(κ) Jᵀ: the virtual joint method for actuators.
  const Vec2 p{0.25, -0.05};
  const double r = p.norm(), phi = std::atan2(p.y(), p.x()), eta = std::acos(r / (2 * kL));
  const double t1 = phi + eta, t2 = phi - eta, s2 = std::pow(std::sin(t1 - t2), 2);
  const double k1 = 2e-4, k2 = 3e-4;  // rad/(N·m)
  Mat2 J;
  J << -kL * std::sin(t1), -kL * std::sin(t2), kL * std::cos(t1), kL * std::cos(t2);
  const Mat2 vjm = J * Vec2(k1, k2).asDiagonal() * J.transpose();
  const Mat2 U_inv = PhysicalModel::link_force_map(kThesis, p);
  const Mat2 D = Vec2(k1 * kL * kL * s2, k2 * kL * kL * s2).asDiagonal();
  EXPECT_LT((U_inv.transpose() * D * U_inv - vjm).norm(), 1e-15);
}

TEST(PhysicalModel, FitRecoversKnownCoefficientsFromNoiselessData) {
  const auto truth = known_physical();
  const auto table = test::synthetic_table([&](const Vec2& p) { return truth->compliance(p); },
                                           [](const Vec2&) { return Vec2::Zero(); });
  const auto fitted = fit_physical_model(group_by_point(table, ForceConvention::measured), kThesis, 1, table.source);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(0.16, 0.28), uy(-0.09, 0.09);
  fitted->set_outside_policy(OutsidePolicy::extrapolate);
  truth->set_outside_policy(OutsidePolicy::extrapolate);
  for (int k = 0; k < 200; ++k) {
    const Vec2 p{ux(rng), uy(rng)};
    EXPECT_LT((fitted->compliance(p) - truth->compliance(p)).norm(), 1e-14 + 1e-9 * truth->compliance(p).norm());
  }
}

TEST(PhysicalModel, IsSymmetricAndGrowsTowardTheStretchedBoundary) {
  const auto model = known_physical();
  model->set_outside_policy(OutsidePolicy::extrapolate);
  const Mat2 c = model->compliance({0.2, 0.03});
  EXPECT_NEAR(c(0, 1), c(1, 0), 1e-18);
  // Along y = 0, the y-compliance rises as r → 2l (U becomes singular).
  double previous = 0.0;
  for (double x = 0.18; x < 0.295; x += 0.01) {
    const double cyy = model->compliance({x, 0.0})(1, 1);
    EXPECT_GT(cyy, previous);
    previous = cyy;
  }
  EXPECT_GT(model->compliance({0.295, 0.0})(1, 1), 5 * model->compliance({0.222132, 0.0})(1, 1));
}

TEST(SymmetricModel, IsSymmetricPositiveDefiniteEverywhereOnTheGrid) {
  // A non-symmetric, noisy field: the symmetric fit must still give C = Cᵀ ≻ 0 at every point.
  const auto table = test::synthetic_table(
      [](const Vec2& p) {
        Mat2 c;
        c << 1.0, 0.4 + p.y() * 5, -0.3, 2.0 + p.x();
        return Mat2(c * 1e-6);
      },
      [](const Vec2&) { return Vec2(1e-5, -2e-5); }, 23e-6 / 3, 5);
  const auto model = make_symmetric_model(group_by_point(table, ForceConvention::measured), table.source);
  for (double x = 0.172132; x <= 0.272133; x += 0.0025) {
    for (double y = -0.075; y <= 0.0750001; y += 0.0025) {
      const Mat2 c = model->compliance({x, y});
      ASSERT_NEAR(c(0, 1), c(1, 0), 1e-20);
      ASSERT_GT(Eigen::SelfAdjointEigenSolver<Mat2>(c).eigenvalues()(0), 0.0);
    }
  }
}

TEST(SymmetricModel, ProjectsAnIndefiniteFitOntoThePositiveDefiniteCone) {
  const auto table = test::synthetic_table(
      [](const Vec2&) {
        Mat2 c;
        c << 1.0, 2.0, 2.0, 1.0;  // eigenvalues 3 and −1 µm/N
        return Mat2(c * 1e-6);
      },
      [](const Vec2&) { return Vec2::Zero(); });
  const GridNode node = fit_symmetric_node(group_by_point(table, ForceConvention::measured)[0], "t");
  EXPECT_TRUE(node.stats["projected_to_positive_definite"].get<bool>());
  EXPECT_NEAR(Eigen::SelfAdjointEigenSolver<Mat2>(node.compliance).eigenvalues()(1), 3e-6, 1e-12);
  EXPECT_NEAR(Eigen::SelfAdjointEigenSolver<Mat2>(node.compliance).eigenvalues()(0), 1e-9, 1e-15);
}

TEST(CrossValidation, PhysicalModelIsExactOnDataItCanRepresent) {
  const auto truth = known_physical();
  truth->set_outside_policy(OutsidePolicy::extrapolate);
  const auto table = test::synthetic_table([&](const Vec2& p) { return truth->compliance(p); },
                                           [](const Vec2&) { return Vec2::Zero(); });
  const CvReport report = cross_validate(group_by_point(table, ForceConvention::measured), kThesis, table.source);
  ASSERT_EQ(report.methods.size(), 6u);
  const CvMethod& physical = report.methods[3];
  EXPECT_EQ(physical.method, FitMethod::physical);
  EXPECT_EQ(physical.predicted, 15);
  EXPECT_LT(physical.max_um, 1e-6);
  const CvMethod& spline = report.methods[5];  // its physical part takes it all, the spline nothing
  EXPECT_EQ(spline.method, FitMethod::physical_spline);
  EXPECT_EQ(spline.predicted, 15);
  EXPECT_LT(spline.max_um, 1e-6);
  const CvMethod& bilinear = report.methods[0];
  EXPECT_EQ(bilinear.predicted, 11);  // all but the four corners
  EXPECT_GT(bilinear.mean_um, 0.1);   // the field is not bilinear
  int interior = 0;
  for (const auto& p : bilinear.points) interior += p.interior ? 1 : 0;
  EXPECT_EQ(interior, 3);
}

TEST(CrossValidation, BilinearIsExactOnABilinearField) {
  const auto table = test::synthetic_table(
      [](const Vec2& p) {
        Mat2 c;
        c << 1.0 + 3 * p.x(), 0.2 * p.y(), 0.1, 2.0 - 5 * p.x() + 4 * p.y();
        return Mat2(c * 1e-6);
      },
      [](const Vec2&) { return Vec2::Zero(); });
  const CvReport report = cross_validate(group_by_point(table, ForceConvention::measured), kThesis, table.source);
  EXPECT_LT(report.methods[0].max_um, 1e-6);
}

TEST(GridModel, BatchEqualsOnePointAtATimeAndEquation412ByHand) {
  // A non-uniform 3 × 4 grid with distinct nodes; points inside, on the lines and outside.
  Grid grid{{0.17, 0.20, 0.27}, {-0.07, -0.01, 0.03, 0.08}};
  std::vector<GridNode> nodes;
  for (double x : grid.xs) {
    for (double y : grid.ys) {
      Mat2 c;
      c << 1.0 + 7 * x, 0.3 * y, -0.2 * y + x, 2.0 + 40 * x * y;
      nodes.push_back({"n", c * 1e-6, Vec2(x, y) * 1e-5, {}});
    }
  }
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> ux(0.15, 0.29), uy(-0.09, 0.10);
  for (OutsidePolicy policy : {OutsidePolicy::clamp, OutsidePolicy::extrapolate}) {
    GridModel model(FitMethod::bilinear, grid, nodes);
    model.set_outside_policy(policy);
    std::vector<Vec2> points{{0.20, -0.01}, {0.17, 0.08}, {0.27, -0.07}};
    for (int i = 0; i < 500; ++i) points.emplace_back(ux(rng), uy(rng));
    std::vector<Mat2> batch(points.size());
    model.compliance_batch(points, batch);
    for (std::size_t k = 0; k < points.size(); ++k) {
      EXPECT_EQ(batch[k], model.compliance(points[k])) << k;
      // Eq. 4.12 with divisions, from the grid's own cell lookup.
      const Vec2 q = policy == OutsidePolicy::clamp ? model.bounds().clamp(points[k]) : points[k];
      int i = 0, j = 0;
      double tx = 0, ty = 0;
      grid.locate(q, i, j, tx, ty);
      const auto at = [&](int di, int dj) { return nodes[static_cast<std::size_t>(grid.node(i + di, j + dj))].compliance; };
      const Mat2 by_hand = (1 - tx) * (1 - ty) * at(0, 0) + (1 - tx) * ty * at(0, 1) + tx * (1 - ty) * at(1, 0) + tx * ty * at(1, 1);
      EXPECT_LT((batch[k] - by_hand).cwiseAbs().maxCoeff(), 1e-20) << k;
    }
  }
}

TEST(ModelFile, RoundTripsEveryMethod) {
  const auto table = test::synthetic_table([](const Vec2& p) { return known_physical()->compliance(p); },
                                           [](const Vec2& p) { return Vec2(p.y() * 1e-4, 2e-6); }, 1e-6, 9);
  test::TempDir dir;
  for (const FitMethod method : {FitMethod::bilinear, FitMethod::symmetric, FitMethod::physical, FitMethod::physical_2,
                                 FitMethod::physical_spline}) {
    auto fitted = fit_model(table, "OC", method, ForceConvention::measured, kinematics::load_robot("oc-gu"));
    fitted.model->set_outside_policy(OutsidePolicy::extrapolate);
    fitted.model->set_zero_force(ZeroForce::thesis_raw);
    const auto path = (dir / (std::string(core::enum_name(method)) + ".json")).string();
    save_model(path, *fitted.model, fitted.provenance);
    const LoadedModel back = load_model_file(core::DataRef{path, false});
    EXPECT_EQ(back.model->outside_policy(), OutsidePolicy::extrapolate);
    EXPECT_EQ(back.model->zero_force(), ZeroForce::thesis_raw);
    EXPECT_EQ(back.provenance.rows, "OC");
    ASSERT_TRUE(back.provenance.geometry.has_value());
    EXPECT_EQ(kinematics::geometry_hash(*back.provenance.geometry), kinematics::load_robot("oc-gu").geometry_hash());
    for (const Vec2& p : {Vec2(0.2, 0.01), Vec2(0.26, -0.07), Vec2(0.28, 0.085)}) {  // the last one off the grid
      const Vec2 F{150.0, -90.0};
      EXPECT_LT((back.model->predict(p, F) - fitted.model->predict(p, F)).norm(), 1e-12) << core::enum_name(method);
    }
  }
}

// The error of loading `doc` written as m.json, with its "m.json:line:column: " prefix checked and removed.
std::string load_error(const nlohmann::json& doc) {
  try {
    (void)model_from_json(core::parse_json_document(doc.dump(2), "m.json"));
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.where().file, "m.json");
    EXPECT_GT(e.where().line, 0) << what;
    EXPECT_EQ(what.rfind(e.where().str() + ": ", 0), 0U) << what;
    return e.message();
  }
  return "";
}

TEST(ModelFile, BadFieldsAreNamed) {
  const auto table = test::synthetic_table([](const Vec2&) { return Mat2(Mat2::Identity() * 1e-6); },
                                           [](const Vec2&) { return Vec2::Zero(); });
  const auto fitted = fit_model(table, "OC", FitMethod::bilinear, ForceConvention::measured, kinematics::load_robot("oc-gu"));
  const nlohmann::json good = model_to_json(*fitted.model, fitted.provenance);
  auto bad = good;
  bad["nodes"][3]["C_um_per_N"] = {{1, 2}, {3}};
  EXPECT_EQ(load_error(bad), "nodes[3].C_um_per_N: must be a 2x2 array [[a, b], [c, d]]");
  bad = good;
  bad["method"] = "spline";
  EXPECT_EQ(load_error(bad), "method: 'spline' is not one of bilinear, symmetric, physical, physical-spline");
  bad = good;
  bad["grid"]["x_mm"] = {1, 1, 2};
  EXPECT_EQ(load_error(bad), "grid.x_mm: must list at least two strictly increasing values");
  bad = good;
  bad.erase("provenance");
  try {
    (void)model_from_json(core::parse_json_document(bad.dump(2), "m.json"));
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "m.json: provenance: missing field");  // no line: the field is not there
  }
  bad = good;
  bad["robot"]["geometry"]["left_distal_mm"] = 151.0;
  EXPECT_EQ(load_error(bad), "robot.geometry_sha256: does not match the geometry recorded beside it (was the file edited?)");
  bad = good;
  bad["outside_policy"] = "wrap";
  EXPECT_NE(load_error(bad).find("outside_policy"), std::string::npos) << load_error(bad);
  EXPECT_NE(load_error(bad).find("error, clamp or extrapolate, got 'wrap'"), std::string::npos) << load_error(bad);
  const auto physical = fit_model(table, "OC", FitMethod::physical, ForceConvention::measured, kinematics::load_robot("oc-gu"));
  bad = model_to_json(*physical.model, physical.provenance);
  bad["D_um_per_N"].erase(2);
  EXPECT_EQ(load_error(bad), "D_um_per_N: order 1 needs 3 entries, got 2");
}

TEST(ModelFactory, UnknownMethodAndMechanismAreNamed) {
  const auto table = test::synthetic_table([](const Vec2&) { return Mat2(Mat2::Identity() * 1e-6); },
                                           [](const Vec2&) { return Vec2::Zero(); });
  const auto robot = kinematics::load_robot("oc-gu");
  EXPECT_THROW((void)parse_fit_method("kriging"), Error);
  try {
    (void)fit_model(table, "SC", FitMethod::bilinear, ForceConvention::measured, robot);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no rows with mechanism 'SC' (the table has: OC)"), std::string::npos);
  }
}

}  // namespace
}  // namespace stiffpath::compliance
