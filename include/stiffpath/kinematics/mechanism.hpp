// The mechanism contract: forward/inverse kinematics at position, velocity and acceleration level.
#pragma once

#include <string>

#include "stiffpath/kinematics/types.hpp"

namespace stiffpath::kinematics {

//! Result of an inverse-kinematics solve that never throws (for the real-time path).
struct InverseResult {
  Vec2 q = Vec2::Zero();            //!< actuated joint angles (θ1, θ2) in rad; zero unless status == ok
  Reach status = Reach::ok;
  double condition_number = 0.0;    //!< of J at q (dimensionless); +inf at a singularity
};

//! A 2-DoF planar mechanism with actuated joints q = (θ1, θ2) and end-effector point p = (x, y).
//! Everything else in stiffpath (compensation, simulation) is written against this contract.
class Mechanism {
 public:
  virtual ~Mechanism() = default;

  //! Position-level forward kinematics p = f(q).
  [[nodiscard]] virtual Vec2 forward(const Vec2& q) const noexcept = 0;
  //! Position-level inverse kinematics with the reach check; never throws, never returns NaN.
  [[nodiscard]] virtual InverseResult solve_inverse(const Vec2& p) const noexcept = 0;
  //! Jacobian J = ∂p/∂q at q.
  [[nodiscard]] virtual Mat2 jacobian(const Vec2& q) const noexcept = 0;
  //! Its time derivative J̇ at (q, q̇).
  [[nodiscard]] virtual Mat2 jacobian_dot(const Vec2& q, const Vec2& qd) const noexcept = 0;
  //! Whether p may be used, with the margin of this mechanism.
  [[nodiscard]] virtual Reach check_reach(const Vec2& p) const noexcept = 0;
  //! 2-norm condition number of J(q).
  [[nodiscard]] virtual double condition_number(const Vec2& q) const noexcept;
  //! Why p is refused, in words with the numbers involved; empty when it is reachable.
  [[nodiscard]] virtual std::string explain(const Vec2& p) const;

  //! Inverse kinematics that throws stiffpath::Error naming the point (in mm) and the reason (explain()).
  [[nodiscard]] Vec2 inverse(const Vec2& p) const;

  //! Velocity level: ṗ = J q̇.
  [[nodiscard]] Vec2 velocity(const Vec2& q, const Vec2& qd) const noexcept { return jacobian(q) * qd; }
  //! Inverse velocity level: q̇ = J⁻¹ ṗ (q must be non-singular, as every solve_inverse result is).
  [[nodiscard]] Vec2 joint_velocity(const Vec2& q, const Vec2& pd) const noexcept;
  //! Acceleration level: p̈ = J q̈ + J̇ q̇.
  [[nodiscard]] Vec2 acceleration(const Vec2& q, const Vec2& qd, const Vec2& qdd) const noexcept;
  //! Inverse acceleration level: q̈ = J⁻¹ (p̈ − J̇ q̇).
  [[nodiscard]] Vec2 joint_acceleration(const Vec2& q, const Vec2& qd, const Vec2& pdd) const noexcept;
};

}  // namespace stiffpath::kinematics
