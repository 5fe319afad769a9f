// The structural C_true: a network of the arms' springs, links and parallelogram bars (fitted in structural_fit.cpp).
#include "stiffpath/simulation/structural_compliance.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "stiffpath/core/error.hpp"
#include "structural_network.hpp"

namespace stiffpath::simulation {

using network::Mat2;
using network::Vec2;
using network::arm_springs;
using network::midpoint;
using network::network_compliance;
using network::pose_at;

double& ArmCompliance::operator[](int k) noexcept {
  double* v[count] = {&actuator_rad_per_Nm, &proximal_bending_per_Nm2, &proximal_axial_per_N,
                      &distal_axial_per_N,  &proximal_bar_m_per_N,     &distal_bar_m_per_N};
  return *v[k];
}
double ArmCompliance::operator[](int k) const noexcept { return const_cast<ArmCompliance&>(*this)[k]; }

StructuralModel::StructuralModel(const kinematics::Robot& robot, std::array<ArmCompliance, 2> arms,
                                 compliance::GridBounds region, BaseCompliance base, Vec2 measured_offset_m)
    : five_bar_(robot.five_bar()), arms_(arms), base_(base), region_(region), offset_(measured_offset_m) {
  for (double v : {base.x_m_per_N, base.y_m_per_N, base.rotation_rad_per_Nm}) {
    if (!(std::isfinite(v) && v >= 0.0)) throw Error("structural model: base compliances must be finite and ≥ 0");
  }
  for (const auto& arm : arms_) {
    for (int k = 0; k < ArmCompliance::count; ++k) {
      if (!(std::isfinite(arm[k]) && arm[k] >= 0.0)) throw Error("structural model: compliances must be finite and ≥ 0");
    }
    if (!arm.proximal_bar_offset_m.allFinite() || !arm.distal_bar_offset_m.allFinite()) {
      throw Error("structural model: bar offsets must be finite");
    }
  }
  if (!offset_.allFinite()) throw Error("structural model: the measured point's offset must be finite");
  springs_ = arm_springs(arms_, five_bar_.geometry());
  set_outside_policy(compliance::OutsidePolicy::extrapolate);
}

Mat2 StructuralModel::compliance(const Vec2& p_in) const noexcept {
  // Beyond reach the structure is evaluated at the nearest point of the measured rectangle.
  Vec2 p = p_in;
  auto inverse = five_bar_.solve_inverse(p);
  if (inverse.status != kinematics::Reach::ok) {
    p = region_.clamp(p_in);
    inverse = five_bar_.solve_inverse(p);
  }
  return network_compliance(pose_at(five_bar_, inverse.q, p), springs_, base_, offset_, p, midpoint(five_bar_));
}

nlohmann::json StructuralModel::parameters() const {
  nlohmann::json arms = nlohmann::json::array();
  for (const auto& a : arms_) {
    arms.push_back({{"actuator_rad_per_Nm", a.actuator_rad_per_Nm},
                    {"proximal_bending_per_Nm2", a.proximal_bending_per_Nm2},
                    {"proximal_axial_per_N", a.proximal_axial_per_N},
                    {"distal_axial_per_N", a.distal_axial_per_N},
                    {"proximal_bar_m_per_N", a.proximal_bar_m_per_N},
                    {"distal_bar_m_per_N", a.distal_bar_m_per_N},
                    {"proximal_bar_offset_mm", {a.proximal_bar_offset_m.x() * 1e3, a.proximal_bar_offset_m.y() * 1e3}},
                    {"distal_bar_offset_mm", {a.distal_bar_offset_m.x() * 1e3, a.distal_bar_offset_m.y() * 1e3}}});
  }
  return {{"arms", arms},
          {"base", {{"x_m_per_N", base_.x_m_per_N}, {"y_m_per_N", base_.y_m_per_N},
                    {"rotation_rad_per_Nm", base_.rotation_rad_per_Nm}}},
          {"measured_offset_mm", {offset_.x() * 1e3, offset_.y() * 1e3}}};
}

}  // namespace stiffpath::simulation
