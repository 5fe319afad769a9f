// Compensator::step: D'Alembert force, predicted deflection, corrected target, inverse kinematics, checks.
#include "stiffpath/compensation/compensator.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <span>

#include "stiffpath/compensation/tip_modes.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::compensation {

const char* describe(Status status) noexcept {
  switch (status) {
    case Status::ok: return "ok";
    case Status::not_finite: return "input sample, or a value computed from it, is not finite";
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

// Mᵀ·v.
Vec2 times_transposed(const Mat2& M, const Vec2& v) noexcept {
  return {M(0, 0) * v.x() + M(1, 0) * v.y(), M(0, 1) * v.x() + M(1, 1) * v.y()};
}

// A finite result, always: a value that overflowed (a huge but finite input, a huge gain) turns the
// step into a not_finite refusal with every vector zeroed.
JointCommand& finite_or_refused(JointCommand& c) noexcept {
  if (finite(c.q_rad) && finite(c.qd_rad_s) && finite(c.qdd_rad_s2) && finite(c.target_m) && finite(c.command_m) &&
      finite(c.force_N) && finite(c.deflection_m) && finite(c.load_torque_Nm) && std::isfinite(c.t_s)) {
    return c;
  }
  const double t = std::isfinite(c.t_s) ? c.t_s : 0.0;
  const bool laser = c.laser_on;
  const int line = c.line;
  c = JointCommand{};
  c.t_s = t;
  c.laser_on = laser;
  c.line = line;
  c.status = Status::not_finite;
  return c;
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
  options_.damping_ratio = options.damping_ratio.value_or(robot.tip_damping_ratio);
  if (!(*options_.damping_ratio >= 0.0 && *options_.damping_ratio <= 2.0)) {
    throw Error("compensation damping ratio must lie in 0..2, got " + std::to_string(*options_.damping_ratio));
  }
  if (options_.method != Method::quasi_static && options_.method != Method::dynamic) {
    throw Error("unknown compensation method");
  }
  effective_gain_ = options_.enabled ? options_.gain : 0.0;
  if (!model_ && effective_gain_ != 0.0) throw Error("compensator needs a compliance model");
  // Without a model (no compensation asked for) nothing is outside and nothing is predicted.
  const double inf = std::numeric_limits<double>::infinity();
  bounds_ = model_ ? model_->bounds() : compliance::GridBounds{-inf, inf, -inf, inf};
  allowed_ = bounds_.grown(compliance::kOutsideMargin_m);
}

JointCommand Compensator::step(const TaskSample& s) const noexcept {
  JointCommand c;
  Lookup lookup;
  if (prepare(s, c, lookup)) {
    std::array<Mat2, 3> Cs;
    look_up(std::span<const Vec2>(lookup.points.data(), lookup.count), Cs);
    finish(s, lookup, Cs, c);
  }
  return finite_or_refused(c);
}

void Compensator::look_up(std::span<const Vec2> points, std::span<Mat2> Cs) const noexcept {
  if (model_) {
    model_->compliance_batch(points, Cs);
  } else {
    for (std::size_t k = 0; k < points.size(); ++k) Cs[k].setZero();
  }
}

bool Compensator::prepare(const TaskSample& s, JointCommand& c, Lookup& lookup) const noexcept {
  c.t_s = s.t_s;
  c.target_m = s.position_m;
  c.laser_on = s.laser_on;
  c.power = s.power;
  c.line = s.line;
  if (!std::isfinite(s.t_s) || !finite(s.position_m) || !finite(s.velocity_m_s) || !finite(s.acceleration_m_s2) ||
      !finite(s.jerk_m_s3) || !finite(s.snap_m_s4) || !finite(s.crackle_m_s5)) {
    c.status = Status::not_finite;
    c.t_s = std::isfinite(s.t_s) ? s.t_s : 0.0;
    c.target_m = Vec2::Zero();
    return false;
  }
  const double m = spec_.moving_mass_kg;
  const double k = effective_gain_;
  c.force_N = -m * s.acceleration_m_s2;
  c.outside_grid = !bounds_.contains(s.position_m);
  if (c.outside_grid && k != 0.0 && model_->outside_policy() == compliance::OutsidePolicy::error &&
      !allowed_.contains(s.position_m)) {
    c.status = Status::outside_grid;
    return false;
  }
  // Δ = model.predict(p, F), written out so that C(p) serves the derivatives too. Ċ and C̈ come from
  // C at p(t ± h) = p ± v·h + a·h²/2, with h such that the points lie ~0.1 mm apart; all three
  // matrices come from one call to the model.
  std::array<Vec2, 3>& points = lookup.points;
  points = {s.position_m, s.position_m, s.position_m};
  lookup.inverse_h = 0.0;
  lookup.count = k != 0.0 ? 3 : 1;
  if (k != 0.0) {
    const double speed = s.velocity_m_s.norm();
    const bool moving = speed * kMaxTimeStep_s > kDerivativeStep_m;
    const double h = moving ? kDerivativeStep_m / speed : kMaxTimeStep_s;
    lookup.inverse_h = moving ? speed / kDerivativeStep_m : 1.0 / kMaxTimeStep_s;
    const Vec2 drift = 0.5 * h * h * s.acceleration_m_s2;
    points[1] = s.position_m + h * s.velocity_m_s + drift;
    points[2] = s.position_m - h * s.velocity_m_s + drift;
    if (options_.method == Method::dynamic) {
      // The tip's stiffness belongs to the mechanism's pose, i.e. the base point p_b = p + k·δ, not to
      // the planned point: one fixed-point step, C at p + k·m·C(p)·a (δ is up to ~1 mm at 5 g, where
      // C changes by a few per mille).
      const Vec2 base_shift = k * m * times(model_->compliance(s.position_m), s.acceleration_m_s2);
      for (Vec2& q : points) q += base_shift;
    }
  }
  return true;
}

void Compensator::finish(const TaskSample& s, const Lookup& lookup, const std::array<Mat2, 3>& Cs,
                         JointCommand& c) const noexcept {
  const double m = spec_.moving_mass_kg;
  const double k = effective_gain_;
  const double inverse_h = lookup.inverse_h;
  const Mat2& C = Cs[0];
  c.deflection_m = times(C, c.force_N);
  if (model_ && model_->zero_force() == compliance::ZeroForce::thesis_raw) c.deflection_m += model_->offset(s.position_m);
  c.command_m = s.position_m - k * c.deflection_m;

  Vec2 pd_cmd = s.velocity_m_s, pdd_cmd = s.acceleration_m_s2;
  if (k != 0.0) {
    // δ₀ = m·C(p(t))·a(t) = −Δ: δ̇₀ = m·(C·j + Ċ·a), δ̈₀ = m·(C·s + 2·Ċ·j + C̈·a).
    const Mat2& C_after = Cs[1];
    const Mat2& C_before = Cs[2];
    const Mat2 C_dot = (C_after - C_before) * (0.5 * inverse_h);
    const Mat2 C_ddot = (C_after - 2.0 * C + C_before) * (inverse_h * inverse_h);
    const Vec2 rate = m * (times(C, s.jerk_m_s3) + times(C_dot, s.acceleration_m_s2));
    const Vec2 curvature =
        m * (times(C, s.snap_m_s4) + 2.0 * times(C_dot, s.jerk_m_s3) + times(C_ddot, s.acceleration_m_s2));
    if (options_.method == Method::dynamic) {
      // δ = δ₀ − T·δ̇₀ + T²·δ̈₀ − T³·δ⃛₀ solves δ + T·δ̇ = δ₀ wherever d⁴δ₀/dt⁴ = 0 (constant crackle, as
      // in the smoothed plans). δ⃛₀ = m·(C·c + 3·Ċ·s + 3·C̈·j) (C⃛ dropped); the rates use T's own rates
      // Ṫ, T̈ from T at the neighbouring points and drop products of two of them and d⁴δ₀/dt⁴.
      // T = 2ζ√(m·C)/s_f: a tip that rings s_f times faster than m·C implies has that much shorter a time constant.
      const double zeta = *options_.damping_ratio / spec_.tip_frequency_scale;
      const Mat2 T = tip_time_constant(C, m, zeta);
      const Mat2 T_after = tip_time_constant(C_after, m, zeta), T_before = tip_time_constant(C_before, m, zeta);
      const Mat2 T_dot = (T_after - T_before) * (0.5 * inverse_h);
      const Mat2 T_ddot = (T_after - 2.0 * T + T_before) * (inverse_h * inverse_h);
      const Vec2 third =
          m * (times(C, s.crackle_m_s5) + 3.0 * times(C_dot, s.snap_m_s4) + 3.0 * times(C_ddot, s.jerk_m_s3));
      const Vec2 T_rate = times(T, rate), T_curvature = times(T, curvature), T_third = times(T, third);
      const Vec2 TT_third = times(T, T_third);
      const Vec2 lag = times(T, T_curvature - TT_third) - T_rate;  // δ − δ₀
      c.deflection_m -= lag;                                        // −δ, in the sign of Δ = C·F
      c.command_m = s.position_m - k * c.deflection_m;
      pd_cmd += k * (rate - times(T_dot, rate) - T_curvature + TT_third);
      pdd_cmd += k * (curvature - times(T_ddot, rate) - 2.0 * times(T_dot, curvature) - T_third);
    } else {
      // The thesis's step, in its original order of operations (k·m·(…)), so its commands stay bit-identical.
      pd_cmd += k * m * (times(C, s.jerk_m_s3) + times(C_dot, s.acceleration_m_s2));
      pdd_cmd += k * m * (times(C, s.snap_m_s4) + 2.0 * times(C_dot, s.jerk_m_s3) + times(C_ddot, s.acceleration_m_s2));
    }
  }

  kinematics::InverseFrame frame;
  const kinematics::InverseResult ik = five_bar_.solve_inverse(c.command_m, frame);
  if (ik.status != kinematics::Reach::ok) {
    c.status = Status::unreachable;
    return;
  }
  c.q_rad = ik.q;
  const Mat2 J_inv = inverse(frame.jacobian);
  c.qd_rad_s = times(J_inv, pd_cmd);
  c.qdd_rad_s2 = times(J_inv, pdd_cmd - times(five_bar_.jacobian_dot(frame, c.qd_rad_s), c.qd_rad_s));
  c.load_torque_Nm = times_transposed(frame.jacobian, m * s.acceleration_m_s2);
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
}

}  // namespace stiffpath::compensation
