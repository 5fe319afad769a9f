// Compensator::step: D'Alembert force, predicted deflection, corrected target, inverse kinematics, checks.
#include "stiffpath/compensation/compensator.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <span>

#include "stiffpath/core/error.hpp"

namespace stiffpath::compensation {

const char* describe(Status status) noexcept {
  switch (status) {
    case Status::ok: return "ok";
    case Status::not_finite: return "input sample is not finite";
    case Status::outside_grid: return "point outside the compliance model's measured region (policy 'error')";
    case Status::unreachable: return "corrected target is not reachable with the mechanism's singularity margin";
    case Status::joint_position: return "joint position limit exceeded";
    case Status::joint_velocity: return "joint velocity limit exceeded";
    case Status::joint_acceleration: return "joint acceleration limit exceeded";
  }
  return "unknown";
}

namespace {
constexpr double kDerivativeStep_m = 1e-4;  // the model's change along the path is taken over ±0.1 mm
constexpr double kMaxTimeStep_s = 1e-3;     // … or ±1 ms of the local motion when moving slowly

bool finite(const Vec2& v) noexcept { return std::isfinite(v.x()) && std::isfinite(v.y()); }

// M·v written out: Eigen's product of fixed 2×2 by 2×1 is not always inlined, and each call then
// sends its operands through memory. Same arithmetic, so the same numbers.
Vec2 times(const Mat2& M, const Vec2& v) noexcept {
  return {M(0, 0) * v.x() + M(0, 1) * v.y(), M(1, 0) * v.x() + M(1, 1) * v.y()};
}

// The 2×2 inverse by the adjugate, as Eigen computes it (one division).
Mat2 inverse(const Mat2& M) noexcept {
  const double inverse_det = 1.0 / (M(0, 0) * M(1, 1) - M(1, 0) * M(0, 1));
  Mat2 out;
  out << M(1, 1) * inverse_det, -M(0, 1) * inverse_det, -M(1, 0) * inverse_det, M(0, 0) * inverse_det;
  return out;
}
}  // namespace

Compensator::Compensator(const kinematics::Robot& robot, std::shared_ptr<const compliance::Model> model,
                         CompensatorOptions options)
    : spec_(robot), five_bar_(robot.five_bar()), model_(std::move(model)), options_(options) {
  if (!std::isfinite(options_.gain) || options_.gain < 0.0) throw Error("compensation gain must be finite and >= 0");
  effective_gain_ = options_.enabled ? options_.gain : 0.0;
  if (!model_ && effective_gain_ != 0.0) throw Error("compensator needs a compliance model");
  // Without a model (no compensation asked for) nothing is outside and nothing is predicted.
  const double inf = std::numeric_limits<double>::infinity();
  bounds_ = model_ ? model_->bounds() : compliance::GridBounds{-inf, inf, -inf, inf};
  allowed_ = bounds_.grown(compliance::kOutsideMargin_m);
}

JointCommand Compensator::step(const TaskSample& s) const noexcept {
  JointCommand c;
  c.t_s = s.t_s;
  c.target_m = s.position_m;
  c.laser_on = s.laser_on;
  c.power = s.power;
  c.line = s.line;
  if (!finite(s.position_m) || !finite(s.velocity_m_s) || !finite(s.acceleration_m_s2) || !finite(s.jerk_m_s3) ||
      !finite(s.snap_m_s4)) {
    c.status = Status::not_finite;
    c.target_m = Vec2::Zero();
    return c;
  }
  const double m = spec_.moving_mass_kg;
  const double k = effective_gain_;
  c.force_N = -m * s.acceleration_m_s2;
  c.outside_grid = !bounds_.contains(s.position_m);
  if (c.outside_grid && k != 0.0 && model_->outside_policy() == compliance::OutsidePolicy::error &&
      !allowed_.contains(s.position_m)) {
    c.status = Status::outside_grid;
    return c;
  }
  // Δ = model.predict(p, F), written out so that C(p) serves the derivatives below too. Ċ and C̈
  // come from C at p(t ± h) = p ± v·h + a·h²/2, with h such that the points lie ~0.1 mm apart; all
  // three matrices come from one call to the model.
  std::array<Vec2, 3> points{s.position_m, s.position_m, s.position_m};
  std::array<Mat2, 3> Cs;
  double inverse_h = 0.0;  // 1/h, so that the differences below take no division
  if (k != 0.0) {
    const double speed = s.velocity_m_s.norm();
    const bool moving = speed * kMaxTimeStep_s > kDerivativeStep_m;
    const double h = moving ? kDerivativeStep_m / speed : kMaxTimeStep_s;
    inverse_h = moving ? speed / kDerivativeStep_m : 1.0 / kMaxTimeStep_s;
    const Vec2 drift = 0.5 * h * h * s.acceleration_m_s2;
    points[1] = s.position_m + h * s.velocity_m_s + drift;
    points[2] = s.position_m - h * s.velocity_m_s + drift;
  }
  if (model_) {
    model_->compliance_batch(std::span<const Vec2>(points.data(), k != 0.0 ? 3 : 1), Cs);
  } else {
    Cs[0].setZero();
  }
  const Mat2& C = Cs[0];
  c.deflection_m = times(C, c.force_N);
  if (model_ && model_->zero_force() == compliance::ZeroForce::thesis_raw) c.deflection_m += model_->offset(s.position_m);
  c.command_m = s.position_m - k * c.deflection_m;

  Vec2 pd_cmd = s.velocity_m_s, pdd_cmd = s.acceleration_m_s2;
  if (k != 0.0) {
    // Δ = −m·C(p(t))·a(t): dΔ/dt = −m·(C·j + Ċ·a), d²Δ/dt² = −m·(C·s + 2·Ċ·j + C̈·a).
    const Mat2& C_after = Cs[1];
    const Mat2& C_before = Cs[2];
    const Mat2 C_dot = (C_after - C_before) * (0.5 * inverse_h);
    const Mat2 C_ddot = (C_after - 2.0 * C + C_before) * (inverse_h * inverse_h);
    pd_cmd += k * m * (times(C, s.jerk_m_s3) + times(C_dot, s.acceleration_m_s2));
    pdd_cmd += k * m * (times(C, s.snap_m_s4) + 2.0 * times(C_dot, s.jerk_m_s3) + times(C_ddot, s.acceleration_m_s2));
  }

  kinematics::InverseFrame frame;
  const kinematics::InverseResult ik = five_bar_.solve_inverse(c.command_m, frame);
  if (ik.status != kinematics::Reach::ok) {
    c.status = Status::unreachable;
    return c;
  }
  c.q_rad = ik.q;
  const Mat2 J_inv = inverse(frame.jacobian);
  c.qd_rad_s = times(J_inv, pd_cmd);
  c.qdd_rad_s2 = times(J_inv, pdd_cmd - times(five_bar_.jacobian_dot(frame, c.qd_rad_s), c.qd_rad_s));
  if (options_.check_limits) {
    int joint = -1;
    switch (kinematics::check_joint_limits(spec_.joints, c.q_rad, c.qd_rad_s, c.qdd_rad_s2, joint)) {
      case kinematics::JointCheck::ok: break;
      case kinematics::JointCheck::position: c.status = Status::joint_position; break;
      case kinematics::JointCheck::velocity: c.status = Status::joint_velocity; break;
      case kinematics::JointCheck::acceleration: c.status = Status::joint_acceleration; break;
    }
    c.joint = joint;
  }
  return c;
}

}  // namespace stiffpath::compensation
