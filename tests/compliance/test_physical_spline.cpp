// The physical-spline model: its thin-plate spline on known fields, its lattice, its files and where cross-validation puts it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/compliance/physical_spline_model.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::compliance {
namespace {

const GridBounds kGrid{0.172132, 0.272132, -0.075, 0.075};

// The thesis's 3 × 5 measurement points.
std::vector<Vec2> grid_points() {
  std::vector<Vec2> out;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 5; ++j) out.emplace_back(0.172132 + 0.05 * i, -0.075 + 0.0375 * j);
  }
  return out;
}

Mat2 sym(double a, double b, double c) {
  Mat2 m;
  m << a, b, b, c;
  return m;
}

double relative(const Mat2& got, const Mat2& want) { return (got - want).norm() / want.norm(); }

TEST(ResidualSpline, ReproducesAnAffineFieldEverywhereWhateverTheSmoothing) {
  // The spline's affine part carries an affine field alone (bending energy 0), so no smoothing moves it.
  const auto field = [](const Vec2& p) { return sym(1e-6 + 4e-6 * p.x(), 0.2e-6 - 1e-6 * p.y(), 2e-6 + 3e-6 * p.y()); };
  std::vector<Mat2> values;
  for (const auto& p : grid_points()) values.push_back(field(p));
  for (const double lambda : {0.0, 0.01, 1.0}) {
    const ResidualSpline s = fit_residual_spline(grid_points(), values, lambda, "test");
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> x(0.15, 0.30), y(-0.1, 0.1);  // beyond the points too
    for (int k = 0; k < 200; ++k) {
      const Vec2 p(x(rng), y(rng));
      EXPECT_LT(relative(s.at(p), field(p)), 1e-9) << lambda << " " << p.transpose();
    }
  }
}

TEST(ResidualSpline, InterpolatesWithoutSmoothingAndStaysCloseWithTheDefault) {
  // A bumpy field no affine function follows: λ = 0 passes through every value, the default within 5 %.
  std::vector<Mat2> values;
  for (const auto& p : grid_points()) {
    values.push_back(sym(std::sin(60 * p.x()) * 1e-7, std::cos(40 * p.y()) * 5e-8, p.x() * p.y() * 1e-5));
  }
  const ResidualSpline exact = fit_residual_spline(grid_points(), values, 0.0, "test");
  const ResidualSpline smooth = fit_residual_spline(grid_points(), values, kResidualSmoothing, "test");
  double scale = 0.0;
  for (const auto& v : values) scale = std::max(scale, v.norm());
  for (std::size_t k = 0; k < values.size(); ++k) {
    EXPECT_LT((exact.at(grid_points()[k]) - values[k]).norm(), 1e-9 * scale) << k;
    EXPECT_LT((smooth.at(grid_points()[k]) - values[k]).norm(), 0.05 * scale) << k;
    EXPECT_GT((smooth.at(grid_points()[k]) - values[k]).norm(), 0.0) << k;  // λ > 0 does smooth
  }
}

TEST(ResidualSpline, RefusesTooFewOrCollinearPointsAndBadSmoothing) {
  const std::vector<Vec2> line{{0.2, 0.0}, {0.21, 0.0}, {0.22, 0.0}, {0.23, 0.0}};
  const std::vector<Mat2> four(4, sym(1e-6, 0.0, 1e-6));
  EXPECT_THROW(fit_residual_spline(line, four, 0.01, "t.csv"), Error);
  EXPECT_THROW(fit_residual_spline({{0.2, 0.0}, {0.21, 0.01}}, {four[0], four[0]}, 0.01, "t.csv"), Error);
  EXPECT_THROW(fit_residual_spline(grid_points(), std::vector<Mat2>(15, four[0]), -1.0, "t.csv"), Error);
  EXPECT_THROW(fit_residual_spline(grid_points(), std::vector<Mat2>(15, four[0]), std::nan(""), "t.csv"), Error);
  try {
    fit_residual_spline(line, four, 0.01, "t.csv");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("t.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("one line"), std::string::npos) << e.what();
  }
}

struct Thesis {
  kinematics::Robot robot = kinematics::load_robot("oc-gu");
  measurement::DisplacementTable table = robot_table(robot);
  std::vector<PointSamples> points = group_by_point(table, ForceConvention::measured);
};

TEST(PhysicalSplineModel, FollowsThePerPointFitsWhereThePhysicalModelCannot) {
  const Thesis t;
  const auto model = fit_physical_spline_model(t.points, t.robot.geometry, t.table.source);
  double physical_ss = 0.0, spline_ss = 0.0;
  for (const auto& point : t.points) {
    const Mat2 measured = fit_point(point, t.table.source).compliance();
    const Mat2 want = 0.5 * (measured + measured.transpose());
    physical_ss += (model->physical().compliance(point.position) - want).squaredNorm();
    spline_ss += (model->compliance(point.position) - want).squaredNorm();
    const Mat2 c = model->compliance(point.position);
    EXPECT_NEAR(c(0, 1), c(1, 0), 1e-12 * c.norm());
  }
  // The thesis's OC points: the physical model leaves ~0.2 µm/N RMS per point, the spline < 1/4 of it.
  EXPECT_LT(std::sqrt(spline_ss), 0.25 * std::sqrt(physical_ss));
  EXPECT_GT(std::sqrt(physical_ss / 15.0), 0.05e-6);  // there was something to follow
}

TEST(PhysicalSplineModel, TheLatticeReadsTheFormulaInsideTheRectangleAndTheFormulaRulesOutside) {
  const Thesis t;
  const auto model = fit_physical_spline_model(t.points, t.robot.geometry, t.table.source);
  ASSERT_NE(model->lattice(), nullptr);
  EXPECT_EQ(model->lattice()->exact_cells(), 0U);  // the field is smooth on the 0.75 mm lattice everywhere
  std::mt19937_64 rng(11);
  const GridBounds b = model->bounds();
  std::uniform_real_distribution<double> x(b.x_min, b.x_max), y(b.y_min, b.y_max);
  double worst = 0.0;
  for (int k = 0; k < 3000; ++k) {
    const Vec2 p(x(rng), y(rng));
    worst = std::max(worst, relative(model->compliance(p), model->exact(p)));
  }
  EXPECT_LT(worst, 2e-5);
  // Outside: clamp holds the spline at the edge, extrapolate continues it; both differ from each other there.
  const Vec2 out(b.x_max + 0.02, 0.0);
  auto copy = fit_physical_spline_model(t.points, t.robot.geometry, t.table.source, false);
  copy->set_outside_policy(OutsidePolicy::clamp);
  const Mat2 clamped = copy->compliance(out);
  EXPECT_LT(relative(clamped, copy->physical().compliance(out) + copy->residual().at(b.clamp(out))), 1e-12);
  EXPECT_EQ(copy->physical().outside_policy(), OutsidePolicy::clamp);  // passed on to the physical part
  copy->set_outside_policy(OutsidePolicy::extrapolate);
  EXPECT_EQ(copy->physical().outside_policy(), OutsidePolicy::extrapolate);
  EXPECT_GT(relative(copy->compliance(out), clamped), 1e-4);
}

TEST(PhysicalSplineModel, ModelFilesRoundTripAndRefuseABrokenSpline) {
  const Thesis t;
  const LoadedModel fitted = fit_model(t.table, "OC", FitMethod::physical_spline, ForceConvention::measured, t.robot);
  ASSERT_EQ(fitted.model->method(), FitMethod::physical_spline);
  const nlohmann::json doc = model_to_json(*fitted.model, fitted.provenance);
  const LoadedModel back = model_from_json(core::parse_json_document(doc.dump(2), "m.json"));
  ASSERT_EQ(back.model->method(), FitMethod::physical_spline);
  for (const Vec2& p : {Vec2(0.2, 0.01), Vec2(0.26, -0.07), Vec2(0.172132, 0.075), Vec2(0.25, 0.0305)}) {
    EXPECT_LT(relative(back.model->compliance(p), fitted.model->compliance(p)), 1e-12) << p.transpose();
  }
  const auto refused = [&](nlohmann::json broken, const std::string& field) {
    try {
      (void)model_from_json(core::parse_json_document(broken.dump(2), "m.json"));
      ADD_FAILURE() << "accepted a file with a broken " << field;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("m.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  nlohmann::json broken = doc;
  broken["residual_spline"]["weights_um_per_N"].erase(0);
  refused(broken, "weights_um_per_N");
  broken = doc;
  broken["residual_spline"]["affine_um_per_N"][1][2] = "x";
  refused(broken, "affine_um_per_N");
  broken = doc;
  broken["residual_spline"]["scale_mm"] = -1.0;
  refused(broken, "scale_mm");
  broken = doc;
  broken["residual_spline"]["weights_um_per_N"][3][0] = 1e12;  // a spline that bends beyond any robot
  refused(broken, "residual_spline");
  broken = doc;
  broken.erase("residual_spline");
  refused(broken, "residual_spline");
}

TEST(PhysicalSplineModel, CrossValidationFavoursItOnTheThesisTables) {
  // Leave-one-out on the thesis's measurements (not on a field of our own): the spline's residual
  // predicts held-out points better than every other method, OC and SC alike.
  for (const char* name : {"oc-gu", "sc-gu"}) {
    const auto robot = kinematics::load_robot(name);
    const auto table = robot_table(robot);
    const CvReport report = cross_validate(group_by_point(table, ForceConvention::measured), robot.geometry, table.source);
    std::vector<std::pair<FitMethod, double>> scores;
    EXPECT_EQ(favoured_method(report, &scores), FitMethod::physical_spline) << name;
    double spline = 0.0, physical = 0.0;
    for (const auto& [method, score] : scores) {
      if (method == FitMethod::physical_spline) spline = score;
      if (method == FitMethod::physical) physical = score;
    }
    EXPECT_LT(spline, 0.8 * physical) << name;
  }
}

}  // namespace
}  // namespace stiffpath::compliance
