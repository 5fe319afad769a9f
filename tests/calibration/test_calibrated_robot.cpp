// A calibration's robot and model files: a second round's correction composed with the first one's over the base model.
#include <gtest/gtest.h>

#include "stiffpath/calibration/calibrated_robot.hpp"
#include "stiffpath/compliance/corrected_model.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::calibration {
namespace {

struct Rounds {
  kinematics::Robot robot;
  std::shared_ptr<compliance::Model> base;
  compliance::Provenance provenance;
  compliance::ComplianceCorrection first, second;
};

compliance::ComplianceCorrection over(const compliance::GridBounds& b) {
  compliance::ComplianceCorrection c;
  c.origin_m = {0.5 * (b.x_min + b.x_max), 0.5 * (b.y_min + b.y_max)};
  c.half_size_m = {0.5 * (b.x_max - b.x_min), 0.5 * (b.y_max - b.y_min)};
  return c;
}

// The model calibrated_robot writes when the robot's model already carries `first` and the plate found `second`.
std::unique_ptr<compliance::Model> second_round(const Rounds& r) {
  compliance::LoadedModel base;
  base.model = std::make_unique<compliance::CorrectedModel>(r.base, r.first);
  base.provenance = r.provenance;
  base.label = "first round";
  Identification id;
  id.after.correction = r.second;
  id.after.damping_ratio = 0.07;
  const CalibratedRobot files = calibrated_robot(r.robot, base, id, "r_model.json");
  EXPECT_DOUBLE_EQ(files.robot["tip_damping_ratio"].get<double>(), 0.07);
  EXPECT_EQ(files.robot["compliance"]["model"].get<std::string>(), "r_model.json");
  return compliance::model_from_json(core::parse_json_document(files.model.dump(), "r_model.json")).model;
}

Rounds rounds() {
  Rounds r;
  r.robot = kinematics::load_robot("oc-gu");
  compliance::LoadedModel loaded = compliance::load_robot_model(r.robot);
  r.provenance = loaded.provenance;
  r.base = std::shared_ptr<compliance::Model>(loaded.model.release());
  r.first = over(r.base->bounds());
  // The second plate over a smaller area, as a plate's marked area is.
  compliance::GridBounds inner = r.base->bounds();
  inner.x_min += 0.01, inner.x_max -= 0.01, inner.y_min += 0.01, inner.y_max -= 0.01;
  r.second = over(inner);
  return r;
}

// Two scales multiply: m·C of 1.10 then 0.95 along x is 1.045, everywhere, exactly.
TEST(CalibratedRobot, TwoRoundsOfScalesMultiply) {
  Rounds r = rounds();
  r.first.sx = {1.10, 0.0, 0.0}, r.first.sy = {0.90, 0.0, 0.0};
  r.second.sx = {0.95, 0.0, 0.0}, r.second.sy = {1.05, 0.0, 0.0};
  const auto model = second_round(r);
  const auto b = r.base->bounds();
  for (const Vec2& p : {Vec2(b.x_min, b.y_min), Vec2(0.5 * (b.x_min + b.x_max), 0.5 * (b.y_min + b.y_max)), Vec2(b.x_max, b.y_max)}) {
    const Mat2 got = model->compliance(p), base = r.base->compliance(p);
    EXPECT_NEAR(got(0, 0) / base(0, 0), 1.10 * 0.95, 1e-9);
    EXPECT_NEAR(got(1, 1) / base(1, 1), 0.90 * 1.05, 1e-9);
    EXPECT_NEAR(got(0, 1) / base(0, 1), std::sqrt(1.10 * 0.95 * 0.90 * 1.05), 1e-9);
  }
}

// Gradients and cross terms: the composed model is the two rounds applied in turn (S₂·S₁·C·S₁·S₂) to within the
// linear refit's error, well under the corrections' own size, over the second plate's area; symmetric throughout.
TEST(CalibratedRobot, TwoRoundsWithGradientsAndCrossTermsComposeWithinTheRefit) {
  Rounds r = rounds();
  r.first.sx = {1.08, 0.04, -0.02}, r.first.sy = {0.94, -0.03, 0.05}, r.first.sxy = {0.03, 0.01, -0.01};
  r.second.sx = {0.97, -0.02, 0.01}, r.second.sy = {1.03, 0.02, -0.02}, r.second.sxy = {-0.02, 0.005, 0.01};
  const auto model = second_round(r);
  const compliance::GridBounds area{r.second.origin_m.x() - r.second.half_size_m.x(), r.second.origin_m.x() + r.second.half_size_m.x(),
                                    r.second.origin_m.y() - r.second.half_size_m.y(), r.second.origin_m.y() + r.second.half_size_m.y()};
  double worst = 0.0, size = 0.0;
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; j <= 4; ++j) {
      const Vec2 p(area.x_min + 0.25 * i * (area.x_max - area.x_min), area.y_min + 0.25 * j * (area.y_max - area.y_min));
      const Mat2 C = r.base->compliance(p);
      const Mat2 M = r.second.matrix(p) * r.first.matrix(p);
      const Mat2 want = M * C * M.transpose(), got = model->compliance(p);
      EXPECT_NEAR(got(0, 1), got(1, 0), 1e-15);
      worst = std::max(worst, (got - want).norm() / want.norm());
      size = std::max(size, (want - C).norm() / C.norm());
    }
  }
  std::printf("composed model against the two rounds in turn: largest relative error %.4f (the corrections: %.3f)\n", worst, size);
  EXPECT_LT(worst, 0.01);
  EXPECT_GT(size, 0.05);
}

}  // namespace
}  // namespace stiffpath::calibration
