// Servo, rigid-kinematics and compliant-tip dynamics of the twin, one symplectic Euler step at a time.
#include "stiffpath/simulation/plant.hpp"

#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "stiffpath/core/error.hpp"

namespace stiffpath::simulation {

Mat2 sqrt_spd(const Mat2& A) noexcept {
  const double s = std::sqrt(std::max(A.determinant(), 0.0));
  const double t = std::sqrt(A.trace() + 2.0 * s);
  return (A + s * Mat2::Identity()) / t;
}

Plant::Plant(const kinematics::FiveBar& robot, std::shared_ptr<const compliance::Model> truth, double mass_kg,
             PlantOptions options)
    : robot_(robot), truth_(std::move(truth)), mass_(mass_kg), options_(options) {
  if (!truth_) throw Error("plant: no true compliance model");
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(mass_kg)) throw Error(fmt::format("plant: mass {} kg must be positive", mass_kg));
  if (!positive(options.step_rate_hz)) throw Error(fmt::format("plant: step_rate_hz {} must be positive", options.step_rate_hz));
  if (!positive(options.servo_bandwidth_hz)) {
    throw Error(fmt::format("plant: servo_bandwidth_hz {} must be positive", options.servo_bandwidth_hz));
  }
  if (!(options.servo_damping >= 0.0) || !(options.tip_damping_ratio >= 0.0) || !std::isfinite(options.servo_damping) ||
      !std::isfinite(options.tip_damping_ratio)) {
    throw Error(fmt::format("plant: damping ratios ({}, {}) must be finite and ≥ 0", options.servo_damping,
                            options.tip_damping_ratio));
  }
  omega_s_ = 2.0 * std::numbers::pi * options.servo_bandwidth_hz;
}

void Plant::reset(const Vec2& q_rad, const Vec2& qd_rad_s) noexcept {
  state_.q_rad = q_rad;
  state_.qd_rad_s = qd_rad_s;
  state_.tip_m = base();
  state_.tip_m_s = base_velocity();
}

Mat2 Plant::stiffness(const Vec2& p) const noexcept { return truth_->compliance(p).inverse(); }

Mat2 Plant::damping(const Vec2& p) const noexcept {
  return 2.0 * options_.tip_damping_ratio * std::sqrt(mass_) * sqrt_spd(stiffness(p));
}

void Plant::step(const JointReference& r, double dt, const Vec2& external_force_N) noexcept {
  // Servos: velocity first, then position with the new velocity (symplectic Euler).
  const Vec2 qdd = r.qdd_rad_s2 + omega_s_ * omega_s_ * (r.q_rad - state_.q_rad) +
                   2.0 * options_.servo_damping * omega_s_ * (r.qd_rad_s - state_.qd_rad_s);
  state_.qd_rad_s += dt * qdd;
  state_.q_rad += dt * state_.qd_rad_s;
  // Tip on its spring and damper to the new base point.
  const Vec2 pb = robot_.forward(state_.q_rad);
  const Vec2 vb = robot_.jacobian(state_.q_rad) * state_.qd_rad_s;
  const Mat2 K = truth_->compliance(pb).inverse();
  const Mat2 D = 2.0 * options_.tip_damping_ratio * std::sqrt(mass_) * sqrt_spd(K);
  const Vec2 force = -K * (state_.tip_m - pb) - D * (state_.tip_m_s - vb) + external_force_N;
  state_.tip_m_s += (dt / mass_) * force;
  state_.tip_m += dt * state_.tip_m_s;
}

double Plant::relative_energy() const noexcept {
  const Vec2 pb = base();
  const Vec2 e = state_.tip_m - pb, v = state_.tip_m_s - base_velocity();
  return 0.5 * mass_ * v.squaredNorm() + 0.5 * e.dot(stiffness(pb) * e);
}

}  // namespace stiffpath::simulation
