// Tests of the real-time compensation step: consistency, zero/mirror/gain properties, derivatives, refusals.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::compensation {
namespace {

// A built-in model that clamps outside its grid: these tests sample around the grid on purpose.
std::shared_ptr<const compliance::Model> thesis(const std::string& name) {
  auto loaded = compliance::load_model(name);
  loaded.model->set_outside_policy(compliance::OutsidePolicy::clamp);
  return std::shared_ptr<const compliance::Model>(loaded.model.release());
}

// The thesis's step (fig. 4.3, quasi-static) at gain k: what these tests check against eqs. 4.4-4.7.
CompensatorOptions quasi_static(double k = 1.0, bool enabled = true, bool check_limits = true) {
  CompensatorOptions o;
  o.gain = k;
  o.enabled = enabled;
  o.check_limits = check_limits;
  o.method = Method::quasi_static;
  return o;
}

// A planar trajectory p(t) = c + A·(sin ωt, sin 2ωt) with its analytic derivatives.
TaskSample lissajous(double t) {
  const double w = 2 * M_PI * 3.0;
  const Vec2 c{0.222, 0.0}, amp{0.04, 0.05};
  TaskSample s;
  s.t_s = t;
  s.position_m = c + Vec2(amp.x() * std::sin(w * t), amp.y() * std::sin(2 * w * t));
  s.velocity_m_s = Vec2(amp.x() * w * std::cos(w * t), amp.y() * 2 * w * std::cos(2 * w * t));
  s.acceleration_m_s2 = Vec2(-amp.x() * w * w * std::sin(w * t), -amp.y() * 4 * w * w * std::sin(2 * w * t));
  s.jerk_m_s3 = Vec2(-amp.x() * w * w * w * std::cos(w * t), -amp.y() * 8 * w * w * w * std::cos(2 * w * t));
  s.snap_m_s4 = Vec2(amp.x() * std::pow(w, 4) * std::sin(w * t), amp.y() * 16 * std::pow(w, 4) * std::sin(2 * w * t));
  return s;
}

// The step as first written (before the throughput work): three separate model calls, divisions
// by h, Eigen's products and inverse, eq. 2.2 and J from the angles. The real-time step now shares work
// between these; it must give the same commands up to rounding.
JointCommand reference_step(const kinematics::Robot& spec, const compliance::Model& model, double k,
                            const TaskSample& s) {
  JointCommand c;
  const double m = spec.moving_mass_kg;
  c.force_N = -m * s.acceleration_m_s2;
  const Mat2 C = model.compliance(s.position_m);
  c.deflection_m = C * c.force_N;
  c.command_m = s.position_m - k * c.deflection_m;
  const double speed = s.velocity_m_s.norm();
  const double h = speed * 1e-3 > 1e-4 ? 1e-4 / speed : 1e-3;
  const Vec2 drift = 0.5 * h * h * s.acceleration_m_s2;
  const Mat2 C_after = model.compliance(s.position_m + h * s.velocity_m_s + drift);
  const Mat2 C_before = model.compliance(s.position_m - h * s.velocity_m_s + drift);
  const Mat2 C_dot = (C_after - C_before) / (2.0 * h);
  const Mat2 C_ddot = (C_after - 2.0 * C + C_before) / (h * h);
  const Vec2 pd = s.velocity_m_s + k * m * (C * s.jerk_m_s3 + C_dot * s.acceleration_m_s2);
  const Vec2 pdd = s.acceleration_m_s2 + k * m * (C * s.snap_m_s4 + 2.0 * C_dot * s.jerk_m_s3 + C_ddot * s.acceleration_m_s2);
  const auto robot = spec.five_bar();
  c.status = robot.check_reach(c.command_m) == kinematics::Reach::ok ? Status::ok : Status::unreachable;
  if (c.status != Status::ok) return c;
  const double phi = std::atan2(c.command_m.y(), c.command_m.x());                         // eq. 2.2
  const double eta = std::acos(c.command_m.norm() / (2.0 * robot.geometry().proximal_m[0]));
  c.q_rad = {phi + eta, phi - eta};
  const Mat2 J = robot.jacobian(c.q_rad);
  c.qd_rad_s = J.inverse() * pd;
  c.qdd_rad_s2 = J.inverse() * (pdd - robot.jacobian_dot(c.q_rad, c.qd_rad_s) * c.qd_rad_s);
  return c;
}

TEST(Compensator, MatchesTheStraightforwardStepToRounding) {
  // Seeded random states over the workspace (inside and around the grid, moving fast and slowly),
  // for the bilinear, physical and extrapolating models and two gains.
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto spec = kinematics::load_robot("oc-gu");
  auto extrapolating = compliance::load_model("thesis-oc");
  extrapolating.model->set_outside_policy(compliance::OutsidePolicy::extrapolate);
  const std::shared_ptr<const compliance::Model> models[] = {
      thesis("thesis-oc"), thesis("thesis-oc-physical"),
      std::shared_ptr<const compliance::Model>(extrapolating.model.release())};
  double worst_q = 0.0;
  for (const auto& model : models) {
    for (double k : {1.0, 0.8}) {
      const Compensator comp(spec, model, quasi_static(k, true, false));
      for (int i = 0; i < 3000; ++i) {
        TaskSample s;
        s.position_m = {0.222 + 0.06 * u(rng), 0.085 * u(rng)};
        const double speed = i % 3 == 0 ? 0.05 : 2.0;  // below and above the 0.1 m/s where h stops growing
        s.velocity_m_s = {speed * u(rng), speed * u(rng)};
        s.acceleration_m_s2 = {50 * u(rng), 50 * u(rng)};
        s.jerk_m_s3 = {1e4 * u(rng), 1e4 * u(rng)};
        s.snap_m_s4 = {1e6 * u(rng), 1e6 * u(rng)};
        const JointCommand a = comp.step(s), b = reference_step(spec, *model, k, s);
        ASSERT_EQ(a.status, b.status);
        EXPECT_LT((a.deflection_m - b.deflection_m).norm(), 1e-18);  // the same C(p), to rounding …
        if (a.status != Status::ok) continue;
        worst_q = std::max(worst_q, (a.q_rad - b.q_rad).cwiseAbs().maxCoeff());
        // … and the derivatives up to the rounding that C̈'s difference over ~0.1 mm amplifies.
        EXPECT_LT((a.qd_rad_s - b.qd_rad_s).norm(), 1e-12 * (1 + b.qd_rad_s.norm())) << i;
        EXPECT_LT((a.qdd_rad_s2 - b.qdd_rad_s2).norm(), 1e-9 * (1 + b.qdd_rad_s2.norm())) << i;
      }
    }
  }
  EXPECT_LT(worst_q, 1e-12);  // the commands: the same to 1e-12 rad
}

TEST(Compensator, CommandedPoseLandsOnThePlanAfterThePredictedDeflection) {
  const auto spec = kinematics::load_robot("oc-gu");
  const Compensator comp(spec, thesis("thesis-oc"), quasi_static());
  const auto robot = spec.five_bar();
  double worst = 0.0, largest = 0.0;
  for (double t = 0.0; t < 0.34; t += 0.0005) {
    const JointCommand c = comp.step(lissajous(t));
    ASSERT_EQ(c.status, Status::ok) << describe(c.status) << " at t = " << t;
    worst = std::max(worst, (robot.forward(c.q_rad) + c.deflection_m - c.target_m).norm());
    largest = std::max(largest, c.deflection_m.norm());
  }
  EXPECT_LT(worst, 1e-6);    // the 1 µm; in fact exact to rounding
  EXPECT_LT(worst, 1e-12);
  EXPECT_GT(largest, 50e-6);  // the test moves: deflections of tens of µm
}

TEST(Compensator, ZeroAccelerationGivesZeroCorrection) {
  const auto spec = kinematics::load_robot("sc-gl");
  const Compensator comp(spec, thesis("thesis-sc"), quasi_static());
  TaskSample s;
  s.position_m = {0.25, -0.06};
  s.velocity_m_s = {0.3, 0.1};
  const JointCommand c = comp.step(s);
  ASSERT_EQ(c.status, Status::ok);
  EXPECT_EQ(c.deflection_m, Vec2::Zero());
  EXPECT_EQ(c.command_m, s.position_m);
  EXPECT_LT((c.q_rad - spec.five_bar().inverse(s.position_m)).norm(), 1e-15);
}

TEST(Compensator, DAlembertForceIsMinusMassTimesAcceleration) {
  const auto spec = kinematics::load_robot("oc-gl");
  const Compensator comp(spec, thesis("thesis-oc"), quasi_static());
  TaskSample s;
  s.position_m = {0.222132, 0.0};
  s.acceleration_m_s2 = {49.03325, 0.0};  // 5 g along +x
  const JointCommand c = comp.step(s);
  EXPECT_NEAR(c.force_N.x(), -3.6 * 49.03325, 1e-12);
  // Δ = C·F at x2y3 and the command moves against it: p_cmd − p = −Δ.
  EXPECT_LT((c.command_m - s.position_m + c.deflection_m).norm(), 1e-16);  // a few ulps of 0.2 m
  EXPECT_LT(c.deflection_m.x(), -50e-6);  // C_xx ≈ 0.59 µm/N × −176.5 N ≈ −104 µm
}

TEST(Compensator, GainZeroEqualsNoCompensationAndGainScales) {
  const auto spec = kinematics::load_robot("oc-gu");
  const auto model = thesis("thesis-oc");
  const Compensator off(spec, model, quasi_static(1.0, false, true)), zero(spec, model, quasi_static(0.0, true, true)),
      half(spec, model, quasi_static(0.5, true, true)), full(spec, model, quasi_static());
  for (double t = 0.0; t < 0.3; t += 0.01) {
    const TaskSample s = lissajous(t);
    const JointCommand a = off.step(s), b = zero.step(s), h = half.step(s), f = full.step(s);
    EXPECT_EQ(a.q_rad, b.q_rad);
    EXPECT_EQ(a.qd_rad_s, b.qd_rad_s);
    EXPECT_EQ(a.command_m, s.position_m);
    EXPECT_LT((h.command_m - s.position_m - 0.5 * (f.command_m - s.position_m)).norm(), 1e-16);
  }
}

TEST(Compensator, MirroredPathGivesMirroredCorrectionsOnASymmetricRobot) {
  // A compliance field symmetric about y = 0 (C(x, −y) = S·C(x, y)·S, S = diag(1, −1)), as the OC
  // build's symmetry implies, on the thesis grid.
  compliance::Grid grid{{0.172132, 0.222132, 0.272132}, {-0.075, -0.0375, 0.0, 0.0375, 0.075}};
  std::vector<compliance::GridNode> nodes;
  for (double x : grid.xs) {
    for (double y : grid.ys) {
      Mat2 c;
      c << 0.6 + x, 0.8 * y, 0.8 * y, 2.0 + 10 * x * x + 30 * y * y;
      nodes.push_back({"n", c * 1e-6, Vec2::Zero(), {}});
    }
  }
  const auto model = std::make_shared<compliance::GridModel>(compliance::FitMethod::bilinear, grid, nodes);
  const Compensator comp(kinematics::load_robot("oc-gu"), model, quasi_static());
  for (double t = 0.0; t < 0.3; t += 0.005) {
    TaskSample s = lissajous(t);
    TaskSample m = s;
    for (Vec2* v : {&m.position_m, &m.velocity_m_s, &m.acceleration_m_s2, &m.jerk_m_s3, &m.snap_m_s4}) v->y() = -v->y();
    const JointCommand a = comp.step(s), b = comp.step(m);
    const Vec2 corr_a = a.command_m - s.position_m, corr_b = b.command_m - m.position_m;
    EXPECT_NEAR(corr_a.x(), corr_b.x(), 1e-15);
    EXPECT_NEAR(corr_a.y(), -corr_b.y(), 1e-15);
    // The five-bar's mirror swaps and negates the joints: θ1(x, −y) = −θ2(x, y).
    EXPECT_NEAR(a.q_rad.x(), -b.q_rad.y(), 1e-12);
  }
}

TEST(Compensator, JointVelocityAndAccelerationMatchDifferencesOfTheCommands) {
  const Compensator comp(kinematics::load_robot("sc-gu"), thesis("thesis-sc-physical"), quasi_static());
  const double h = 1e-5;
  for (double t = 0.01; t < 0.3; t += 0.013) {
    const JointCommand before = comp.step(lissajous(t - h)), now = comp.step(lissajous(t)),
                       after = comp.step(lissajous(t + h));
    const Vec2 qd_numeric = (after.q_rad - before.q_rad) / (2 * h);
    const Vec2 qdd_numeric = (after.q_rad - 2 * now.q_rad + before.q_rad) / (h * h);
    EXPECT_LT((now.qd_rad_s - qd_numeric).norm(), 1e-6 * (1 + now.qd_rad_s.norm())) << t;
    // Ċ and C̈ are differences over ~0.1 mm: agreement to 1e-4 relative.
    EXPECT_LT((now.qdd_rad_s2 - qdd_numeric).norm(), 1e-4 * (1 + now.qdd_rad_s2.norm())) << t;
  }
}

TEST(Compensator, RefusesUnreachableTargetsAndJointLimitViolationsWithoutNaN) {
  const auto spec = kinematics::load_robot("oc-gu");
  const Compensator comp(spec, thesis("thesis-oc"), quasi_static());
  TaskSample s;
  s.position_m = {0.299, 0.0};
  JointCommand c = comp.step(s);
  EXPECT_EQ(c.status, Status::unreachable);
  EXPECT_TRUE(c.q_rad.allFinite());
  s.position_m = {0.222, 0.0};
  s.velocity_m_s = {0.0, 10.0};  // ω = v/(2l·cos η) = 45 rad/s at (222, 0) mm: above the 40 rad/s limit
  c = comp.step(s);
  EXPECT_EQ(c.status, Status::joint_velocity);
  EXPECT_GE(c.joint, 0);
  s.velocity_m_s = {std::nan(""), 0.0};
  c = comp.step(s);
  EXPECT_EQ(c.status, Status::not_finite);
  EXPECT_TRUE(c.q_rad.allFinite() && c.target_m.allFinite() && c.command_m.allFinite());
}

TEST(Compensator, OutsideGridPolicyErrorRefusesBeyondTheMarginOnly) {
  auto loaded = compliance::load_model("thesis-oc");
  ASSERT_EQ(loaded.model->outside_policy(), compliance::OutsidePolicy::error);  // the default
  const std::shared_ptr<const compliance::Model> model(loaded.model.release());
  const Compensator comp(kinematics::load_robot("oc-gu"), model, quasi_static());
  TaskSample s;
  s.acceleration_m_s2 = {10.0, 0.0};
  s.position_m = {0.150, 0.0};  // 22 mm left of the grid
  EXPECT_EQ(comp.step(s).status, Status::outside_grid);
  s.position_m = {0.200, 0.0};
  EXPECT_EQ(comp.step(s).status, Status::ok);
  // The grid's edge y = 75 mm: 0.9 mm beyond it is clamped and counted, 1.1 mm beyond it refused.
  ASSERT_EQ(compliance::kOutsideMargin_m, 1e-3);
  s.position_m = {0.222132, 0.0759};
  JointCommand c = comp.step(s);
  EXPECT_EQ(c.status, Status::ok);
  EXPECT_TRUE(c.outside_grid);
  EXPECT_EQ(c.deflection_m, model->compliance({0.222132, 0.075}) * c.force_N);
  s.position_m = {0.222132, 0.0761};
  EXPECT_EQ(comp.step(s).status, Status::outside_grid);
  // Without compensation nothing is refused for the model's sake.
  const Compensator off(kinematics::load_robot("oc-gu"), model, quasi_static(1.0, false, true));
  EXPECT_EQ(off.step(s).status, Status::ok);
}

TEST(Compensator, RejectsBadGain) {
  const auto spec = kinematics::load_robot("oc-gu");
  EXPECT_THROW(Compensator(spec, thesis("thesis-oc"), quasi_static(-1.0, true, true)), Error);
  EXPECT_THROW(Compensator(spec, thesis("thesis-oc"), quasi_static(std::nan(""), true, true)), Error);
  EXPECT_THROW(Compensator(spec, nullptr), Error);
}

}  // namespace
}  // namespace stiffpath::compensation
