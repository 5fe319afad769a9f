// The thesis's 2-DoF five-bar (parallelogram "hidden robot"): both actuators at A0, four links of length l.
#pragma once

#include "stiffpath/kinematics/mechanism.hpp"

namespace stiffpath::kinematics {

//! Passive angles of the five-bar's parallelogram loops (eq. 2.2): θ3 = θ2, θ4 = θ1.
struct PassiveAngles {
  double theta3_rad = 0.0;
  double theta4_rad = 0.0;
};

//! The five-bar of thesis section 2.2: C = l·(e^{iθ1} + e^{iθ2}) (eq. 2.1), working mode
//! θ1 = φ + η, θ2 = φ − η with η = acos(r / 2l) (eq. 2.2). Singular at r = 2l (η = 0) and r = 0
//! (η = π/2); the Jacobian's condition number is max(tan η, cot η).
class FiveBar final : public Mechanism {
 public:
  //! `link_length_m` > 0; margin as documented in SingularityMargin.
  explicit FiveBar(double link_length_m = 0.150, SingularityMargin margin = {});

  [[nodiscard]] double link_length() const noexcept { return l_; }
  [[nodiscard]] const SingularityMargin& margin() const noexcept { return margin_; }

  //! Eq. 2.1: x = l(cos θ1 + cos θ2), y = l(sin θ1 + sin θ2).
  [[nodiscard]] Vec2 forward(const Vec2& q) const noexcept override;
  //! Eq. 2.2 with the reach check of check_reach().
  [[nodiscard]] InverseResult solve_inverse(const Vec2& p) const noexcept override;
  //! The same, also giving J at the solution without further trigonometry: cos θ1,2 and sin θ1,2
  //! follow from cos φ = x/r, sin φ = y/r, cos η = r/2l, sin η = √(1 − cos²η). `jacobian` is left
  //! unchanged unless the status is ok. For the real-time path.
  [[nodiscard]] InverseResult solve_inverse(const Vec2& p, Mat2& jacobian) const noexcept;
  //! J̇ from J: each column of J rotates with its joint, J̇ = R90·J·diag(q̇).
  [[nodiscard]] static Mat2 jacobian_dot_from(const Mat2& jacobian, const Vec2& qd) noexcept {
    Mat2 Jd;
    Jd << -jacobian(1, 0) * qd.x(), -jacobian(1, 1) * qd.y(), jacobian(0, 0) * qd.x(), jacobian(0, 1) * qd.y();
    return Jd;
  }
  //! J = l [−sin θ1, −sin θ2; cos θ1, cos θ2].
  [[nodiscard]] Mat2 jacobian(const Vec2& q) const noexcept override;
  //! J̇ = l [−cos θ1 θ̇1, −cos θ2 θ̇2; −sin θ1 θ̇1, −sin θ2 θ̇2].
  [[nodiscard]] Mat2 jacobian_dot(const Vec2& q, const Vec2& qd) const noexcept override;
  [[nodiscard]] Reach check_reach(const Vec2& p) const noexcept override;
  //! Closed form sqrt((1 + |cos(θ1 − θ2)|) / (1 − |cos(θ1 − θ2)|)).
  [[nodiscard]] double condition_number(const Vec2& q) const noexcept override;

  //! Eq. 2.2's passive angles for the actuated angles q.
  [[nodiscard]] static PassiveAngles passive_angles(const Vec2& q) noexcept;
  //! Condition number at a radius r from A0 (used to turn the margin into radii).
  [[nodiscard]] double condition_number_at_radius(double r) const noexcept;

 private:
  double l_;
  double inverse_2l_;  // 1 / (2l), for the real-time inverse
  SingularityMargin margin_;
};

}  // namespace stiffpath::kinematics
