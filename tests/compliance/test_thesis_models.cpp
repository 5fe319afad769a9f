// The compliance models on the thesis data set: hand-checked fits, cross-validation targets, SPD and speed-free checks.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/physical_model.hpp"
#include "stiffpath/compliance/tool_point.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::compliance {
namespace {

const PointFit& find(const std::vector<PointFit>& fits, const std::string& id) {
  for (const auto& f : fits) {
    if (f.id == id) return f;
  }
  throw std::runtime_error("no point " + id);
}

// Least squares by the textbook formulas on values typed in from the seed's tables.
LineFit by_hand(const std::vector<double>& kgf, const std::vector<double>& d_mm, double sign) {
  std::vector<double> f, d;
  for (std::size_t i = 0; i < kgf.size(); ++i) {
    f.push_back(sign * (kgf[i] - 0.11) * 9.80665);
    d.push_back(d_mm[i] * 1e-3);
  }
  return fit_line(f, d);
}

TEST(ThesisFits, MatchHandComputedLeastSquares) {
  const auto table = measurement::load_displacement_table(measurement::thesis_dataset()).filter("OC");
  const auto fits = fit_points(table);
  // OC x1y3, +x (table 2.2): step 1's Δx is garbled ("27"), so steps 2-5: 0.059, 0.094, 0.129, 0.164 mm.
  const LineFit m = by_hand({9.92, 14.89, 19.83, 24.86}, {0.059, 0.094, 0.129, 0.164}, +1.0);
  const PointFit& x1y3 = find(fits, "x1y3");
  EXPECT_EQ(x1y3.dx_fx.n, 4);
  EXPECT_NEAR(x1y3.dx_fx.slope, m.slope, 1e-6 * m.slope);  // the CSV rounds F_N to 0.1 mN
  EXPECT_NEAR(x1y3.dx_fx.slope * 1e6, 0.717, 1e-3);  // µm/N, (0.164 − 0.059) mm / 146.5 N ≈ 0.717
  // OC x3y5, −y (table 2.3): Δy = −0.319, −0.658, −0.998, −1.331, −1.671 mm under Fy < 0.
  const LineFit v = by_hand({5, 9.92, 14.89, 19.83, 24.86}, {-0.319, -0.658, -0.998, -1.331, -1.671}, -1.0);
  const PointFit& x3y5 = find(fits, "x3y5");
  EXPECT_NEAR(x3y5.dy_fy.slope, v.slope, 1e-6 * v.slope);
  EXPECT_NEAR(x3y5.dy_fy.intercept, v.intercept, 1e-9);  // 1 nm
  EXPECT_GT(x3y5.dy_fy.slope, 6.8e-6);  // Δy follows −Fy: positive compliance, ≈ 6.9 µm/N
  EXPECT_GT(x3y5.dy_fy.r_squared, 0.999);
}

TEST(ThesisCrossValidation, OcMeetsTheTargetsAndBeatsBilinear) {
  const auto table = measurement::load_displacement_table(measurement::thesis_dataset()).filter("OC");
  const CvReport r = cross_validate(group_by_point(table, ForceConvention::measured), kinematics::FiveBarGeometry::thesis(0.150), "thesis");
  const CvMethod& bilinear = r.methods[0];
  const CvMethod& physical = r.methods[3];
  ASSERT_EQ(bilinear.method, FitMethod::bilinear);
  ASSERT_EQ(physical.method, FitMethod::physical);
  // The issue: interpolating the middle column linearly from its neighbours misses by about 90 µm.
  EXPECT_NEAR(bilinear.interior_mean_um, 90.0, 5.0);
  // Target for our best model there: ≤ 25 µm mean, close to the arm's ±23 µm.
  EXPECT_LT(physical.interior_mean_um, 25.0);
  EXPECT_EQ(physical.predicted, 15);
  EXPECT_LT(physical.mean_um, bilinear.mean_um);
}

TEST(ThesisCrossValidation, ScPhysicalBeatsBilinearToo) {
  const auto table = measurement::load_displacement_table(measurement::thesis_dataset()).filter("SC");
  const CvReport r = cross_validate(group_by_point(table, ForceConvention::measured), kinematics::FiveBarGeometry::thesis(0.150), "thesis");
  EXPECT_LT(r.methods[3].interior_mean_um, 0.5 * r.methods[0].interior_mean_um);
}

TEST(ThesisModels, SymmetricAndPhysicalArePositiveDefiniteOverTheWorkspace) {
  for (const std::string build : {"OC", "SC"}) {
    const auto table = measurement::load_displacement_table(measurement::thesis_dataset());
    for (const FitMethod method : {FitMethod::symmetric, FitMethod::physical}) {
      const auto m = fit_model(table, build, method, ForceConvention::measured, kinematics::load_robot("oc-gu"));
      for (double x = 0.172132; x <= 0.272133; x += 0.005) {
        for (double y = -0.075; y <= 0.0750001; y += 0.005) {
          const Mat2 c = m.model->compliance({x, y});
          ASSERT_NEAR(c(0, 1), c(1, 0), 1e-20) << build << " " << core::enum_name(method);
          ASSERT_GT(Eigen::SelfAdjointEigenSolver<Mat2>(c).eigenvalues()(0), 0.0) << build << " " << core::enum_name(method) << " " << x
                                                                                   << ", " << y;
        }
      }
    }
  }
}

TEST(ThesisModels, BuiltInModelsAreTheThesisBilinearFits) {
  const auto oc = load_model("thesis-oc");
  EXPECT_EQ(oc.model->method(), FitMethod::bilinear);
  EXPECT_EQ(oc.provenance.rows, "OC");
  EXPECT_EQ(oc.provenance.robot, "oc-gu");
  EXPECT_EQ(oc.provenance.sha256.size(), 64u);
  // At x3y5 the y compliance is the −y table's slope: ≈ 6.9 µm/N.
  EXPECT_NEAR(oc.model->compliance({0.272132, 0.075})(1, 1) * 1e6, 6.9, 0.1);
  EXPECT_EQ(load_model("thesis-sc-physical").model->method(), FitMethod::physical);
  EXPECT_THROW((void)load_model("thesis-xx"), Error);
  EXPECT_THROW((void)load_model("thesis-oc-kriging"), Error);
}

TEST(ThesisModels, ToolPointLeverFollowsTheAngularDeflections) {
  const auto table = measurement::load_displacement_table(measurement::thesis_dataset()).filter("OC");
  const auto fits = fit_points(table);
  std::shared_ptr<const GridModel> angular = make_angular_model(fits, "thesis");
  std::shared_ptr<const Model> at_G = make_bilinear_model(fits, "thesis");
  const ToolPointModel tool(at_G, angular, 0.050);
  const Vec2 p{0.222132, 0.0}, F{250.0, 0.0};
  // Table 3.4, x2y3: ry ≈ 0.082° at 250 N → Δx_tool − Δx_G = −d·ry ≈ −0.05·0.00143 m ≈ −72 µm.
  const Vec2 change = tool.predict(p, F) - at_G->predict(p, F);
  EXPECT_NEAR(change.x() * 1e6, -0.050 * angular->compliance(p)(1, 0) * 250.0 * 1e6, 1e-9);
  EXPECT_LT(change.x() * 1e6, -60.0);
  EXPECT_GT(change.x() * 1e6, -85.0);
}

}  // namespace
}  // namespace stiffpath::compliance
