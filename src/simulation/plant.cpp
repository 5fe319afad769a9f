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
             PlantOptions options, std::shared_ptr<const compliance::Model> cg_lever)
    : robot_(robot), truth_(std::move(truth)), mass_(mass_kg), options_(options), lever_(std::move(cg_lever)) {
  if (!truth_) throw Error("plant: no true compliance model");
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(mass_kg)) throw Error(fmt::format("plant: mass {} kg must be positive", mass_kg));
  if (!positive(options.step_rate_hz)) throw Error(fmt::format("plant: step_rate_hz {} must be positive", options.step_rate_hz));
  if (!positive(options.servo_bandwidth_hz)) {
    throw Error(fmt::format("plant: servo_bandwidth_hz {} must be positive", options.servo_bandwidth_hz));
  }
  if (!positive(options.servo_damping)) throw Error(fmt::format("plant: servo_damping {} must be positive", options.servo_damping));
  if (!positive(options.motor_inertia_kg_m2)) {
    throw Error(fmt::format("plant: motor_inertia_kg_m2 {} must be positive", options.motor_inertia_kg_m2));
  }
  options_.tip_damping_ratio = options.tip_damping_ratio.value_or(kDefaultTipDampingRatio);
  if (!(*options_.tip_damping_ratio >= 0.0) || !std::isfinite(*options_.tip_damping_ratio)) {
    throw Error(fmt::format("plant: tip damping ratio {} must be finite and ≥ 0", *options_.tip_damping_ratio));
  }
  if (!(options.load_feedforward >= 0.0 && options.load_feedforward <= 2.0)) {
    throw Error(fmt::format("plant: load_feedforward {} outside [0, 2]", options.load_feedforward));
  }
  if (!(options.controller_mass_kg >= 0.0) || !std::isfinite(options.controller_mass_kg)) {
    throw Error(fmt::format("plant: controller_mass_kg {} must be finite and ≥ 0", options.controller_mass_kg));
  }
  omega_s_ = 2.0 * std::numbers::pi * options.servo_bandwidth_hz;
  controller_mass_ = options.controller_mass_kg > 0.0 ? options.controller_mass_kg : mass_kg;
  // The drive is tuned for its motor plus the platform's rigid inertia at the middle of the measured rectangle.
  const compliance::GridBounds b = truth_->bounds();
  const auto centre = robot_.solve_inverse(Vec2(0.5 * (b.x_min + b.x_max), 0.5 * (b.y_min + b.y_max)));
  const Mat2 jc = centre.status == kinematics::Reach::ok ? robot_.jacobian(centre.q) : Mat2::Zero();
  const Mat2 jtj = jc.transpose() * jc;
  tuning_inertia_ = Vec2(options.motor_inertia_kg_m2 + controller_mass_ * jtj(0, 0),
                         options.motor_inertia_kg_m2 + controller_mass_ * jtj(1, 1));
  kv_ = 2.0 * options.servo_damping * omega_s_ * tuning_inertia_;
  kp_ = omega_s_ / (2.0 * options.servo_damping);
}

void Plant::reset(const Vec2& q_rad, const Vec2& qd_rad_s) noexcept {
  cache_valid_ = false;
  state_.q_rad = q_rad;
  state_.qd_rad_s = qd_rad_s;
  state_.tip_m = base();
  state_.tip_m_s = base_velocity();
}

Mat2 Plant::stiffness(const Vec2& p) const noexcept {
  if (lever_) return Mat2(truth_->compliance(p) + lever_->compliance(p)).inverse();
  return truth_->compliance(p).inverse();
}

Mat2 Plant::damping(const Vec2& p) const noexcept {
  const Mat2 k = stiffness(p);
  return 2.0 * *options_.tip_damping_ratio * std::sqrt(mass_) * sqrt_spd(lever_ ? Mat2(0.5 * (k + k.transpose())) : k);
}

Vec2 Plant::static_joint_error(const Vec2& q_rad, const Vec2& force_N) const noexcept {
  return (robot_.jacobian(q_rad).transpose() * force_N).cwiseQuotient(kp_ * kv_);
}

void Plant::step(const JointReference& r, double dt, const Vec2& external_force_N) noexcept {
  if (!at_cache()) update_cache(robot_.forward(state_.q_rad), robot_.jacobian(state_.q_rad));
  const Vec2 pb0 = cache_pb_;
  const Mat2 j0 = cache_J_;
  const Vec2 vb0 = j0 * state_.qd_rad_s;
  if (options_.servo_feels_load) {
    // Drive: torque feed-forward, P/P cascade and the platform's load; the velocity loop's damping is taken
    // implicitly (on J_m alone it is far faster than the step): J_m q̇⁺ = J_m q̇ + dt(τ − K_v q̇⁺).
    const double jm = options_.motor_inertia_kg_m2;
    Vec2 tau = jm * r.qdd_rad_s2;
    if (options_.load_feedforward > 0.0 && options_.load_feedforward_from_command) {
      tau += options_.load_feedforward * (robot_.jacobian(r.q_rad).transpose() * r.load_force_N);
    } else if (options_.load_feedforward > 0.0) {
      const Mat2 jr = robot_.jacobian(r.q_rad);
      const Vec2 a_ref = jr * r.qdd_rad_s2 + robot_.jacobian_dot(r.q_rad, r.qd_rad_s) * r.qd_rad_s;
      tau += options_.load_feedforward * controller_mass_ * (jr.transpose() * a_ref);
    }
    tau += kv_.cwiseProduct(r.qd_rad_s + kp_ * (r.q_rad - state_.q_rad));
    tau += j0.transpose() * (cache_K_ * (state_.tip_m - pb0) + cache_D_ * (state_.tip_m_s - vb0));
    state_.qd_rad_s = (jm * state_.qd_rad_s + dt * tau).cwiseQuotient(Vec2::Constant(jm) + dt * kv_);
  } else {
    // The ideal servo: unloaded, it tracks as q̈ = q̈_ref + ω_s²(q_ref − q) + 2ζ_sω_s(q̇_ref − q̇), explicitly.
    const Vec2 qdd = r.qdd_rad_s2 + omega_s_ * omega_s_ * (r.q_rad - state_.q_rad) +
                     2.0 * options_.servo_damping * omega_s_ * (r.qd_rad_s - state_.qd_rad_s);
    state_.qd_rad_s += dt * qdd;
  }
  state_.q_rad += dt * state_.qd_rad_s;
  // Tip on its spring and damper to the new base point.
  // p_b, J, K and D at the new joints serve this step's tip and the next step's joints.
  update_cache(robot_.forward(state_.q_rad), robot_.jacobian(state_.q_rad));
  const Vec2 pb = cache_pb_;
  const Vec2 vb = cache_J_ * state_.qd_rad_s;
  const Vec2 force = -cache_K_ * (state_.tip_m - pb) - cache_D_ * (state_.tip_m_s - vb) + external_force_N;
  state_.tip_m_s += (dt / mass_) * force;
  state_.tip_m += dt * state_.tip_m_s;
}

void Plant::update_cache(const Vec2& pb, const Mat2& jacobian) noexcept {
  cache_pb_ = pb;
  cache_J_ = jacobian;
  cache_K_ = stiffness(pb);
  cache_D_ = 2.0 * *options_.tip_damping_ratio * std::sqrt(mass_) *
             sqrt_spd(lever_ ? Mat2(0.5 * (cache_K_ + cache_K_.transpose())) : cache_K_);
  cache_q_ = state_.q_rad;
  cache_valid_ = true;
}

double Plant::relative_energy() const noexcept {
  const Vec2 pb = base();
  const Vec2 e = state_.tip_m - pb, v = state_.tip_m_s - base_velocity();
  return 0.5 * mass_ * v.squaredNorm() + 0.5 * e.dot(stiffness(pb) * e);
}

}  // namespace stiffpath::simulation
