// Tests of the per-point fits (eqs. 4.8–4.11) and the bilinear grid model (eq. 4.12) on known fields.
#include <gtest/gtest.h>

#include <random>

#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/core/line_fit.hpp"
#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/core/error.hpp"
#include "synthetic_table.hpp"

namespace stiffpath::compliance {
namespace {

// A smooth, non-symmetric field: C varies linearly in x and quadratically in y (µm/N scale).
Mat2 field(const Vec2& p) {
  Mat2 c;
  c << 1.0 + 4.0 * (p.x() - 0.17), 0.3 * p.y() / 0.075, -0.2 * p.y() / 0.075, 2.0 + 10.0 * p.y() * p.y();
  return c * 1e-6;
}
Vec2 offset_field(const Vec2& p) { return Vec2{5e-6 + 1e-4 * p.y(), -3e-6} ; }

TEST(LineFit, MatchesHandComputedLeastSquares) {
  // x = 1..5, y = 2x + 1 with residuals (+0.1, −0.1, 0, +0.1, −0.1): slope 1.98, intercept 1.06 by hand.
  const double x[] = {1, 2, 3, 4, 5};
  const double y[] = {3.1, 4.9, 7.0, 9.1, 10.9};
  const LineFit f = fit_line(x, y);
  EXPECT_EQ(f.n, 5);
  EXPECT_NEAR(f.slope, 1.98, 1e-12);        // Sxy / Sxx = 19.8 / 10
  EXPECT_NEAR(f.intercept, 1.06, 1e-12);    // 7.0 − 1.98·3
  // SSE and Syy computed independently of the implementation.
  double sse = 0.0;
  for (int i = 0; i < 5; ++i) sse += std::pow(y[i] - (1.98 * x[i] + 1.06), 2);
  EXPECT_NEAR(f.slope_stderr, std::sqrt(sse / 3.0 / 10.0), 1e-12);
  EXPECT_NEAR(f.r_squared, 1.0 - sse / 39.24, 1e-12);  // Syy = 2·(3.9² + 2.1²) = 39.24
  const double one[] = {1.0};
  EXPECT_LT(fit_line(one, one).n, 2);
  const double same[] = {2.0, 2.0, 2.0};
  EXPECT_LT(fit_line(same, y).n, 2);
}

TEST(PointFit, RecoversTheFieldAndOffsetsExactlyWithoutNoise) {
  const auto table = test::synthetic_table(field, offset_field);
  const auto fits = fit_points(table);
  ASSERT_EQ(fits.size(), 15u);
  for (const auto& f : fits) {
    EXPECT_LT((f.compliance() - field(f.position)).norm(), 1e-15) << f.id;
    // Each of the four series carries the full offset component, so n + p = 2·offset_x.
    EXPECT_NEAR(f.offset().x(), 2 * offset_field(f.position).x(), 1e-15);
    EXPECT_NEAR(f.dy_fy.r_squared, 1.0, 1e-12);
  }
}

TEST(PointFit, NominalForcesChangeTheSlopeByTheForceRatio) {
  const auto table = test::synthetic_table(field, [](const Vec2&) { return Vec2::Zero(); });
  const auto measured = fit_points(table, ForceConvention::measured);
  const auto nominal = fit_points(table, ForceConvention::nominal);
  // Δ = c·F_N with F_N = (kgf − 0.11)·g; regressed on 50…250 N the slope is c·cov(F_N, F_nom)/var(F_nom).
  const double kgf[5] = {5.0, 9.92, 14.89, 19.83, 24.86};
  double cov = 0.0, var = 0.0, mean_measured = 0.0;
  for (double k : kgf) mean_measured += (k - 0.11) * 9.80665 / 5.0;
  for (int s = 0; s < 5; ++s) {
    cov += ((kgf[s] - 0.11) * 9.80665 - mean_measured) * (50.0 * (s + 1) - 150.0);
    var += (50.0 * (s + 1) - 150.0) * (50.0 * (s + 1) - 150.0);
  }
  EXPECT_NEAR(nominal[0].dx_fx.slope / measured[0].dx_fx.slope, cov / var, 1e-12);
  EXPECT_NEAR(cov / var, 0.9734, 1e-4);  // nominal forces understate the force by 2.7 %
}

TEST(PointFit, TooFewStepsNamesThePoint) {
  auto table = test::synthetic_table(field, offset_field);
  std::erase_if(table.rows, [](const measurement::DisplacementRow& r) {
    return r.point == "x2y4" && r.direction == measurement::ForceDirection::minus_y && r.step > 1;
  });
  try {
    (void)fit_points(table);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("point x2y4: fewer than two usable load steps for the fit dx vs Fy"),
              std::string::npos)
        << e.what();
  }
}

TEST(PointFit, MissingCellsAreSkipped) {
  auto table = test::synthetic_table(field, offset_field);
  for (auto& r : table.rows) {
    if (r.point == "x1y1" && r.step == 3) r.dx_m.reset();
  }
  const auto fits = fit_points(table);
  EXPECT_EQ(fits[0].dx_fx.n, 4);
  EXPECT_EQ(fits[0].dy_fx.n, 5);
  EXPECT_LT((fits[0].compliance() - field(fits[0].position)).norm(), 1e-15);
}

TEST(BilinearModel, ReproducesGridValuesAndIsLinearAlongEdges) {
  const auto table = test::synthetic_table(field, offset_field, 2e-6, 7);
  const auto fits = fit_points(table);
  const auto model = make_bilinear_model(fits, table.source);
  for (const auto& f : fits) {
    EXPECT_LT((model->compliance(f.position) - f.compliance()).norm(), 1e-18) << f.id;
    EXPECT_LT((model->offset(f.position) - f.offset()).norm(), 1e-18) << f.id;
  }
  // Along the edge x = 172.132 mm between y = −75 and −37.5 mm, C is linear in y.
  const Mat2 a = model->compliance({0.172132, -0.075}), b = model->compliance({0.172132, -0.0375});
  for (double t : {0.1, 0.25, 0.5, 0.9}) {
    EXPECT_LT((model->compliance({0.172132, -0.075 + t * 0.0375}) - ((1 - t) * a + t * b)).norm(), 1e-18);
  }
  // Eq. 4.12 at the centre of a cell is the mean of its four corners.
  const Mat2 centre = model->compliance({0.197132, -0.05625});
  const Mat2 mean = 0.25 * (model->compliance({0.172132, -0.075}) + model->compliance({0.222132, -0.075}) +
                            model->compliance({0.172132, -0.0375}) + model->compliance({0.222132, -0.0375}));
  EXPECT_LT((centre - mean).norm(), 1e-18);
}

TEST(BilinearModel, PredictIsLinearInForceAndRawModeAddsTheIntercepts) {
  const auto table = test::synthetic_table(field, offset_field, 2e-6, 8);
  const auto model = make_bilinear_model(fit_points(table), table.source);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> ux(0.172132, 0.272132), uy(-0.075, 0.075), uf(-200, 200);
  for (int k = 0; k < 500; ++k) {
    const Vec2 p{ux(rng), uy(rng)}, f1{uf(rng), uf(rng)}, f2{uf(rng), uf(rng)};
    const double a = uf(rng) / 100.0;
    EXPECT_LT((model->predict(p, a * f1 + f2) - (a * model->predict(p, f1) + model->predict(p, f2))).norm(), 1e-18);
    EXPECT_LT(model->predict(p, Vec2::Zero()).norm(), 1e-30);
  }
  model->set_zero_force(ZeroForce::thesis_raw);
  const Vec2 p{0.2, 0.01};
  EXPECT_LT((model->predict(p, Vec2::Zero()) - model->offset(p)).norm(), 1e-18);
  EXPECT_GT(model->offset(p).norm(), 1e-6);
}

TEST(BilinearModel, OutsidePolicies) {
  const auto table = test::synthetic_table(field, offset_field);
  const auto model = make_bilinear_model(fit_points(table), table.source);
  const Vec2 outside{0.290, 0.090};
  EXPECT_FALSE(model->inside(outside));
  EXPECT_LT((model->compliance(outside) - model->compliance({0.272132, 0.075})).norm(), 1e-18);  // clamp
  model->set_outside_policy(OutsidePolicy::extrapolate);
  // The field is linear in x at fixed y, so the edge cell's extension continues it exactly in x.
  const Vec2 beyond_x{0.290, 0.075};
  EXPECT_NEAR(model->compliance(beyond_x)(0, 0), field(beyond_x)(0, 0), 1e-15);
}

TEST(Grid, IncompleteGridIsRejectedNamingTheMissingNode) {
  auto table = test::synthetic_table(field, offset_field);
  std::erase_if(table.rows, [](const measurement::DisplacementRow& r) { return r.point == "x3y2"; });
  try {
    (void)make_bilinear_model(fit_points(table), table.source);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing measured at (272.132, -37.500) mm"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stiffpath::compliance
