// The CG lever of the twin's platform from the robot's measured tilts (tables 3.4–3.7) and its CG height.
#include "stiffpath/simulation/cg_lever.hpp"

#include <nlohmann/json.hpp>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/compliance/tool_point.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::simulation {
namespace {

class LeverModel final : public compliance::Model {
 public:
  LeverModel(std::shared_ptr<const compliance::GridModel> angular, double h) : angular_(std::move(angular)), h_(h) {
    set_outside_policy(compliance::OutsidePolicy::clamp);
  }
  [[nodiscard]] std::string description() const override { return "CG lever"; }
  [[nodiscard]] compliance::Mat2 compliance(const compliance::Vec2& p) const noexcept override {
    const compliance::Mat2 a = angular_->compliance(bounds().clamp(p));
    compliance::Mat2 l;
    l << a(1, 0), -a(0, 0), a(1, 1), -a(0, 1);
    return h_ * l;
  }
  [[nodiscard]] compliance::GridBounds bounds() const noexcept override { return angular_->bounds(); }

 private:
  std::shared_ptr<const compliance::GridModel> angular_;
  double h_;
};

class SumModel final : public compliance::Model {
 public:
  SumModel(std::shared_ptr<const compliance::Model> a, std::shared_ptr<const compliance::Model> b)
      : a_(std::move(a)), b_(std::move(b)) {
    set_outside_policy(compliance::OutsidePolicy::extrapolate);
  }
  [[nodiscard]] std::string description() const override { return a_->description() + " + " + b_->description(); }
  [[nodiscard]] compliance::Mat2 compliance(const compliance::Vec2& p) const noexcept override {
    return a_->compliance(p) + b_->compliance(p);
  }
  [[nodiscard]] compliance::GridBounds bounds() const noexcept override { return a_->bounds(); }

 private:
  std::shared_ptr<const compliance::Model> a_, b_;
};

}  // namespace

std::shared_ptr<const compliance::Model> make_loaded_compliance(std::shared_ptr<const compliance::Model> truth,
                                                                std::shared_ptr<const compliance::Model> lever) {
  if (!lever) return truth;
  return std::make_shared<SumModel>(std::move(truth), std::move(lever));
}

std::shared_ptr<const compliance::Model> make_cg_lever(const kinematics::Robot& robot) {
  if (robot.cg_height_m == 0.0 || robot.compliance.table.empty()) return nullptr;
  const auto table = compliance::robot_table(robot);
  try {
    std::shared_ptr<const compliance::GridModel> angular = compliance::make_angular_model(
        compliance::fit_points(table, compliance::ForceConvention::measured), table.source);
    return std::make_shared<LeverModel>(std::move(angular), robot.cg_height_m);
  } catch (const Error&) {
    return nullptr;  // no tilts at every point, or not a grid: no lever can be derived from the data
  }
}

}  // namespace stiffpath::simulation
