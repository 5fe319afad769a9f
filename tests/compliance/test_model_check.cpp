// The physics check of compliance models: against eigenvalues of the symmetric part (an independent oracle), on the
// thesis's models (all pass), on a negated model (refused at load and at fit, with the point), at a grid node.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "stiffpath/compliance/fit_budget.hpp"
#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/compliance/model_check.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "synthetic_table.hpp"

namespace stiffpath::compliance {
namespace {

// The same matrix everywhere on a 100 × 150 mm rectangle.
class ConstantModel final : public Model {
 public:
  explicit ConstantModel(const Mat2& c) : c_(c) {}
  [[nodiscard]] std::string description() const override { return "constant"; }
  [[nodiscard]] Mat2 compliance(const Vec2&) const noexcept override { return c_; }
  [[nodiscard]] GridBounds bounds() const noexcept override { return {0.172, 0.272, -0.075, 0.075}; }

 private:
  Mat2 c_;
};

// FᵀCF > 0 for every F exactly when the smallest eigenvalue of (C + Cᵀ)/2 is positive.
TEST(ModelCheck, PositiveDefiniteExactlyWhenTheSymmetricPartsEigenvaluesArePositive) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> entry(-2e-6, 2e-6);
  int refused = 0, accepted = 0;
  for (int k = 0; k < 2000; ++k) {
    Mat2 c;
    c << entry(rng), entry(rng), entry(rng), entry(rng);
    const Eigen::SelfAdjointEigenSolver<Mat2> eig(0.5 * (c + c.transpose()));
    const bool definite = eig.eigenvalues().minCoeff() > 0.0;
    const auto defect = find_model_defect(ConstantModel(c));
    EXPECT_EQ(!defect.has_value(), definite) << c;
    if (defect) {
      EXPECT_EQ(defect->word, "PHYSICS");
      ++refused;
    } else {
      ++accepted;
    }
  }
  EXPECT_GT(refused, 100);  // both outcomes are exercised
  EXPECT_GT(accepted, 100);
  // Not exactly symmetric but positive definite, as measured compliances are: accepted.
  Mat2 measured;
  measured << 1.2e-6, 0.3e-6, 0.1e-6, 2.0e-6;
  EXPECT_FALSE(find_model_defect(ConstantModel(measured)).has_value());
  // Beyond 1000 µm/N, or not finite: RANGE.
  EXPECT_EQ(find_model_defect(ConstantModel(Mat2::Identity() * 2e-3))->word, "RANGE");
  EXPECT_EQ(find_model_defect(ConstantModel(Mat2::Identity() * std::nan("")))->word, "RANGE");
}

TEST(ModelCheck, EveryThesisModelIsPhysicalAndANegatedOneIsRefusedAtLoadAndAtFit) {
  for (const char* preset : {"oc-gu", "sc-gu"}) {
    const auto robot = kinematics::load_robot(preset);
    for (const auto& [method, name] : core::EnumNames<FitMethod>::names) {
      const auto model = load_robot_model(robot, {.model = "", .method = method});
      EXPECT_FALSE(find_model_defect(*model.model).has_value()) << preset << " " << name;
    }
  }
  // The physical model of OC with every D coefficient negated, as a model file: refused at D_um_per_N.
  const auto robot = kinematics::load_robot("oc-gu");
  const auto fitted = load_robot_model(robot, {.model = "", .method = FitMethod::physical});
  nlohmann::json doc = model_to_json(*fitted.model, fitted.provenance);
  for (auto& row : doc["D_um_per_N"]) {
    for (auto& v : row) v = -v.get<double>();
  }
  try {
    (void)model_from_json(core::parse_json_document(doc.dump(2), "neg.json"));
    FAIL();
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("neg.json:2:3: D_um_per_N: PHYSICS: the model's compliance at (", 0), 0U) << what;
    EXPECT_NE(what.find("not positive definite"), std::string::npos) << what;
  }
  // A table whose displacements are negated: the fit is refused where the table enters.
  auto table = test::synthetic_table([](const Vec2&) { Mat2 c; c << -1.5e-6, 0.1e-6, 0.1e-6, -1.2e-6; return c; },
                                     [](const Vec2&) { return Vec2::Zero(); });
  try {
    (void)fit_model(table, "OC", FitMethod::bilinear, ForceConvention::measured, robot);
    FAIL();
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("synthetic.csv: PHYSICS: the model's compliance at (", 0), 0U) << what;
    EXPECT_NE(what.find("no model made: the bilinear model fitted to this table (rows OC)"), std::string::npos) << what;
  }
}

// A bilinear model slightly negative at one node: within 0.5 mm of it, between the lattice's points (2.55 mm and
// 3.8 mm apart), so only the check at the nodes, where a bilinear model has its extremes, finds it.
TEST(ModelCheck, AGridModelIsCheckedAtEveryNode) {
  const auto table = test::synthetic_table(
      [](const Vec2& p) {
        Mat2 c = Mat2::Identity() * 1e-6;
        if (std::abs(p.x() - 0.222132) < 1e-9 && std::abs(p.y() - 0.0375) < 1e-9) c(1, 1) = -0.01e-6;
        return c;
      },
      [](const Vec2&) { return Vec2::Zero(); });
  try {
    (void)fit_model(table, "OC", FitMethod::bilinear, ForceConvention::measured, kinematics::load_robot("oc-gu"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at (222.132, 37.500) mm"), std::string::npos) << e.what();
  }
}

// A table of many points: cross-validation (auto) is refused before it starts, a named method is not; a table of
// many samples is refused for any fit.
TEST(FitBudget, BeyondTheBudgetsTheWorkIsRefusedBeforeItStarts) {
  measurement::DisplacementTable table{"many.csv", {}, {}};
  for (std::size_t k = 0; k <= max_cv_points; ++k) {
    for (auto dir : {measurement::ForceDirection::plus_x, measurement::ForceDirection::plus_y}) {
      for (int s = 1; s <= 2; ++s) {
        measurement::DisplacementRow r;
        r.point = "p" + std::to_string(k);
        r.direction = dir;
        r.x_m = 0.18 + 0.004 * static_cast<double>(k % 20);  // a 20 × 21 grid
        r.y_m = -0.06 + 0.006 * static_cast<double>(k / 20);
        r.step = s;
        r.force_N = r.nominal_force_N = 50.0 * s;
        r.force_kgf = r.force_N / 9.80665;
        r.dx_m = (dir == measurement::ForceDirection::plus_x ? 1e-6 : 0.0) * r.force_N;
        r.dy_m = (dir == measurement::ForceDirection::plus_y ? 1e-6 : 0.0) * r.force_N;
        table.rows.push_back(r);
      }
    }
  }
  const auto robot = kinematics::load_robot("oc-gu");
  try {
    (void)fit_model(table, "", std::nullopt, ForceConvention::measured, robot);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("many.csv: LIMIT: cross-validation refits every method once per point; it "
                                         "takes at most 400 points and 20000 samples, this table has 401 points"),
              std::string::npos)
        << e.what();
  }
  try {
    (void)fit_model(table, "", FitMethod::physical_0, ForceConvention::measured, robot);
  } catch (const Error& e) {
    ADD_FAILURE() << e.what();
  }
  const auto points = group_by_point(table, ForceConvention::measured);
  EXPECT_THROW(check_cv_budget(points, "many.csv"), Error);
  auto fewer = points;
  fewer.resize(max_cv_points);
  EXPECT_NO_THROW(check_cv_budget(fewer, "many.csv"));
  // Samples: one point's samples repeated until they are one more than any fit's 100 000.
  PointSamples one = fewer.front();
  one.samples.assign(max_fit_samples, one.samples.front());
  EXPECT_NO_THROW(check_fit_budget({one}, FitMethod::bilinear, "heavy.csv"));
  one.samples.push_back(one.samples.front());
  EXPECT_THROW(check_fit_budget({one}, FitMethod::bilinear, "heavy.csv"), Error);
}

}  // namespace
}  // namespace stiffpath::compliance
