// Dynamic inversion against an independent tip integrator: the compensated base makes the tip follow the plan.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <functional>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compensation/tip_modes.hpp"
#include "stiffpath/compliance/model_factory.hpp"

namespace stiffpath::compensation {
namespace {

// The thesis's bilinear model (C only continuous: Ċ steps at its grid lines), or the physical model fitted
// to the same data (smooth).
std::shared_ptr<const compliance::Model> thesis_oc(const char* name = "thesis-oc") {
  auto loaded = compliance::load_model(name);
  loaded.model->set_outside_policy(compliance::OutsidePolicy::clamp);
  return std::shared_ptr<const compliance::Model>(loaded.model.release());
}

// A rest-to-rest move from a to b in time T along the septic smoothstep s(τ) = 35τ⁴ − 84τ⁵ + 70τ⁶ − 20τ⁷
// (v, a and j zero at both ends), with its analytic derivatives; at rest outside [0, T].
TaskSample septic_move(const Vec2& a, const Vec2& b, double T, double t) {
  const double tau = std::clamp(t / T, 0.0, 1.0);
  const double s = tau * tau * tau * tau * (35 - 84 * tau + 70 * tau * tau - 20 * tau * tau * tau);
  const double s1 = 140 * std::pow(tau, 3) * std::pow(1 - tau, 3);
  const double s2 = 420 * tau * tau * std::pow(1 - tau, 2) * (1 - 2 * tau);
  const double s3 = 840 * tau * (1 - tau) * (1 - 5 * tau + 5 * tau * tau);
  const double s4 = 840 * (1 - 12 * tau + 30 * tau * tau - 20 * tau * tau * tau);
  const double s5 = 840 * (-12 + 60 * tau - 60 * tau * tau);
  const bool moving = t > 0.0 && t < T;
  TaskSample out;
  out.t_s = t;
  const Vec2 d = b - a;
  out.position_m = a + s * d;
  if (moving) {
    out.velocity_m_s = s1 / T * d;
    out.acceleration_m_s2 = s2 / (T * T) * d;
    out.jerk_m_s3 = s3 / (T * T * T) * d;
    out.snap_m_s4 = s4 / (T * T * T * T) * d;
    out.crackle_m_s5 = s5 / std::pow(T, 5) * d;
  }
  return out;
}

// K^{1/2} by an eigen-decomposition (independent of the closed form the compensator uses).
Mat2 sqrt_by_eigen(const Mat2& K) {
  Eigen::EigenSolver<Mat2> solver(K);
  const Eigen::Matrix2cd V = solver.eigenvectors();
  const Eigen::Vector2cd root = solver.eigenvalues().cwiseSqrt();
  return (V * root.asDiagonal() * V.inverse()).real();
}

// Integrates m·p̈ = −K(p_b)(p − p_b) − D(p_b)(ṗ − ṗ_b), D = 2ζ√m·K^{1/2}, K = C⁻¹, by RK4 at 200 kHz,
// the base following `base(t)` exactly; returns the largest distance of the tip from `plan(t)`.
double tip_error(const std::function<Vec2(double)>& base, const std::function<Vec2(double)>& plan,
                 const compliance::Model& model, double m, double zeta, double duration) {
  const double h = 5e-6, eps = 1e-6;
  const auto base_velocity = [&](double t) -> Vec2 { return (base(t + eps) - base(t - eps)) / (2 * eps); };
  const auto accel = [&](double t, const Vec2& p, const Vec2& v) {
    const Vec2 pb = base(t);
    const Mat2 K = model.compliance(pb).inverse();
    const Mat2 D = 2 * zeta * std::sqrt(m) * sqrt_by_eigen(K);
    return Vec2((-K * (p - pb) - D * (v - base_velocity(t))) / m);
  };
  Vec2 p = base(0.0), v = Vec2::Zero();
  double worst = 0.0;
  for (double t = 0.0; t < duration; t += h) {
    const Vec2 k1v = accel(t, p, v), k1p = v;
    const Vec2 k2v = accel(t + h / 2, p + h / 2 * k1p, v + h / 2 * k1v), k2p = v + h / 2 * k1v;
    const Vec2 k3v = accel(t + h / 2, p + h / 2 * k2p, v + h / 2 * k2v), k3p = v + h / 2 * k2v;
    const Vec2 k4v = accel(t + h, p + h * k3p, v + h * k3v), k4p = v + h * k3v;
    p += h / 6 * (k1p + 2 * k2p + 2 * k3p + k4p);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    worst = std::max(worst, (p - plan(t + h)).norm());
  }
  return worst;
}

struct Case {
  Vec2 from, to;
  double duration_s;
};

// 5 g moves: an off-grid y line (x = 247.132 mm, mid-cell) and a diagonal across the workspace.
const Case kCases[] = {{{0.247132, -0.075}, {0.247132, 0.075}, 0.15},
                       {{0.190, -0.060}, {0.255, 0.050}, 0.14}};

double run_case(const Case& c, Method method, double zeta_model, double zeta_tip) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto model = thesis_oc();
  CompensatorOptions o;
  o.method = method;
  o.damping_ratio = zeta_model;
  const Compensator comp(robot, model, o);
  const auto plan = [&](double t) { return septic_move(c.from, c.to, c.duration_s, t).position_m; };
  const auto base = [&](double t) {
    const JointCommand cmd = comp.step(septic_move(c.from, c.to, c.duration_s, t));
    EXPECT_EQ(cmd.status, Status::ok);
    return cmd.command_m;
  };
  return tip_error(base, plan, *model, robot.moving_mass_kg, zeta_tip, c.duration_s + 0.05);
}

TEST(DynamicInversion, PeakAccelerationOfTheCasesIsAboutFiveG) {
  for (const Case& c : kCases) {
    double peak = 0.0;
    for (double t = 0; t < c.duration_s; t += 1e-4) {
      peak = std::max(peak, septic_move(c.from, c.to, c.duration_s, t).acceleration_m_s2.norm());
    }
    EXPECT_GT(peak, 40.0);
    EXPECT_LT(peak, 65.0);
  }
}

TEST(DynamicInversion, TipWithKnownParametersFollowsThePlanWithinOneMicrometre) {
  for (const Case& c : kCases) {
    for (const double zeta : {0.02, 0.05, 0.1, 0.2}) {
      // The closed form is exact while the plan's d⁵p/dt⁵ is constant; where a derivative steps (here
      // the snap at the start and end of the move) it jumps by T²·C·m·Δs, T = 2ζ√m·C^{1/2}, and the
      // tip rings: ~3 µm at ζ = 0.2 (T ≈ 1.6 ms), ≤ 0.2 µm at the default 0.05.
      const double error = run_case(c, Method::dynamic, zeta, zeta);
      EXPECT_LT(error, zeta <= 0.1 ? 1e-6 : 4e-6) << "zeta " << zeta;
      std::printf("dynamic inversion: zeta %.2f, tip error %.3f um\n", zeta, error * 1e6);
    }
  }
}

TEST(DynamicInversion, QuasiStaticLeavesTheDampingForceUncorrected) {
  // The same tip with the thesis's correction: the damper's force D·δ̇ is not compensated, so the
  // tip lags by ~T·δ̇ (several µm at 5 g); this is what the dynamic method removes.
  for (const Case& c : kCases) {
    const double error = run_case(c, Method::quasi_static, 0.05, 0.05);
    EXPECT_GT(error, 3e-6);
    std::printf("quasi-static: zeta 0.05, tip error %.3f um\n", error * 1e6);
  }
}

TEST(DynamicInversion, ZeroDampingIsTheStaticOffsetAtTheBasePoint) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto model = thesis_oc();
  CompensatorOptions dyn;
  dyn.method = Method::dynamic;
  dyn.damping_ratio = 0.0;
  CompensatorOptions quasi;
  quasi.method = Method::quasi_static;
  const Compensator a(robot, model, dyn), b(robot, model, quasi);
  for (double t = 0.0; t < 0.14; t += 0.003) {
    const TaskSample s = septic_move(kCases[1].from, kCases[1].to, 0.14, t);
    const JointCommand ca = a.step(s), cb = b.step(s);
    // ζ = 0: δ = m·C(p_b)·a with the base point p_b = p + m·C(p)·a (one fixed-point step).
    const double m = robot.moving_mass_kg;
    const Vec2 base = s.position_m + m * model->compliance(s.position_m) * s.acceleration_m_s2;
    const Vec2 expected = s.position_m + m * model->compliance(base) * s.acceleration_m_s2;
    EXPECT_LT((ca.command_m - expected).norm(), 1e-15);
    EXPECT_LT((cb.command_m - (s.position_m + m * model->compliance(s.position_m) * s.acceleration_m_s2)).norm(), 1e-15);
  }
}

TEST(DynamicInversion, CommandedVelocityIsTheRateOfTheCommandedPosition) {
  // ω and α of the dynamic command against central differences of its angles.
  const auto robot = kinematics::load_robot("oc-gu");
  CompensatorOptions o;
  o.method = Method::dynamic;
  const Compensator comp(robot, thesis_oc("thesis-oc-physical"), o);  // smooth C: differences are meaningful
  const Case& c = kCases[1];
  const double e = 1e-5;
  for (double t = 0.01; t < c.duration_s - 0.01; t += 0.007) {
    const JointCommand mid = comp.step(septic_move(c.from, c.to, c.duration_s, t));
    const JointCommand after = comp.step(septic_move(c.from, c.to, c.duration_s, t + e));
    const JointCommand before = comp.step(septic_move(c.from, c.to, c.duration_s, t - e));
    const Vec2 qd = (after.q_rad - before.q_rad) / (2 * e);
    const Vec2 qdd = (after.qd_rad_s - before.qd_rad_s) / (2 * e);
    EXPECT_LT((mid.qd_rad_s - qd).norm(), 1e-4 * (1 + qd.norm())) << t;
    EXPECT_LT((mid.qdd_rad_s2 - qdd).norm(), 2e-3 * (1 + qdd.norm())) << t;
  }
}

TEST(TipModes, SquareRootAndFrequencyAgainstHandValues) {
  Mat2 A;
  A << 4.0, 0.0, 0.0, 9.0;
  const Mat2 r = matrix_sqrt(A);
  EXPECT_NEAR(r(0, 0), 2.0, 1e-15);
  EXPECT_NEAR(r(1, 1), 3.0, 1e-15);
  Mat2 S;  // symmetric, not diagonal: the root squares back
  S << 2.0e-6, 0.5e-6, 0.5e-6, 1.0e-6;
  EXPECT_LT((matrix_sqrt(S) * matrix_sqrt(S) - S).norm(), 1e-18);
  // 3.6 kg on C = diag(1, 4) µm/N: the soft direction gives f = 1/(2π√(3.6·4e-6)) = 41.94 Hz.
  Mat2 C;
  C << 1e-6, 0.0, 0.0, 4e-6;
  EXPECT_NEAR(lowest_natural_frequency_hz(C, 3.6), 1.0 / (2 * M_PI * std::sqrt(3.6 * 4e-6)), 1e-9);
  Mat2 bad;
  bad << -1.0, 0.0, 0.0, 1.0;
  EXPECT_EQ(matrix_sqrt(bad), Mat2::Zero());
  EXPECT_EQ(lowest_natural_frequency_hz(Mat2::Constant(NAN), 3.6), 0.0);
}

}  // namespace
}  // namespace stiffpath::compensation
