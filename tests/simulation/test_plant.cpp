// Plant physics: rest, static deflection C_true·F, natural frequency and damping, no energy growth.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <Eigen/Eigenvalues>
#include <random>

#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/simulation/plant.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::simulation {
namespace {

struct Fixture {
  kinematics::Robot spec = kinematics::load_robot("oc-gu");
  std::shared_ptr<const compliance::Model> truth = make_true_compliance(kinematics::load_robot("oc-gu"));
  Plant plant(PlantOptions o = {}) const { return Plant(spec.five_bar(), truth, spec.moving_mass_kg, o); }
  Vec2 q_at(const Vec2& p) const { return spec.five_bar().inverse(p); }
};

JointReference hold(const Vec2& q) { return {q, Vec2::Zero(), Vec2::Zero()}; }

TEST(Plant, SqrtSpdSquaresBack) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 50; ++i) {
    Mat2 B;
    B << u(rng), u(rng), u(rng), u(rng);
    const Mat2 A = B * B.transpose() + 0.1 * Mat2::Identity();
    const Mat2 R = sqrt_spd(A);
    EXPECT_LT((R * R - A).norm(), 1e-12 * A.norm());
    EXPECT_NEAR(R(0, 1), R(1, 0), 1e-15);
    EXPECT_GT(R.determinant(), 0.0);
  }
}

TEST(Plant, AtRestStaysAtRest) {
  const Fixture f;
  for (const Vec2& p : {Vec2(0.222132, 0.0), Vec2(0.18, -0.07), Vec2(0.27, 0.07)}) {
    Plant plant = f.plant();
    const Vec2 q = f.q_at(p);
    plant.reset(q);
    for (int i = 0; i < 2000; ++i) plant.step(hold(q), 5e-5);
    EXPECT_LT((plant.state().tip_m - p).norm(), 1e-12);
    EXPECT_LT(plant.state().tip_m_s.norm(), 1e-12);
    EXPECT_LT((plant.state().q_rad - q).norm(), 1e-14);
  }
}

TEST(Plant, ConstantForceGivesStaticDeflection) {
  const Fixture f;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(0.175, 0.27), uy(-0.07, 0.07), uf(-200, 200);
  for (int trial = 0; trial < 6; ++trial) {
    const Vec2 p(ux(rng), uy(rng)), F(uf(rng), uf(rng));
    PlantOptions o;
    o.tip_damping_ratio = 0.5;  // settle quickly; the static answer does not depend on damping
    Plant plant = f.plant(o);
    const Vec2 q = f.q_at(p);
    plant.reset(q);
    for (int i = 0; i < 8000; ++i) plant.step(hold(q), 5e-5, F);  // 0.4 s ≫ 1/(ζω)
    // The spring deflects by C_true·F relative to the base point, wherever the loaded servo has let it sit.
    const Vec2 base = plant.base();
    const Vec2 expected = f.truth->compliance(base) * F;
    const Vec2 got = plant.state().tip_m - base;
    EXPECT_LT((got - expected).norm(), 1e-3 * expected.norm()) << trial;
  }
}

// The period symplectic Euler gives a mode (ω, ζ) at step h: its one-step map v⁺ = (1 − 2ζωh)v − ω²h·x,
// x⁺ = x + h·v⁺ has eigenvalues √det·e^{±iθ} with cos θ = tr/(2√det): period 2πh/θ. At ζ = 0 it is
// 2π/ω·(1 − (ωh)²/24 + …); the damping, taken explicitly, adds an error of first order in ζωh.
double symplectic_euler_period(double omega, double zeta, double h) {
  const double det = 1.0 - 2.0 * zeta * omega * h, trace = 2.0 - omega * omega * h * h - 2.0 * zeta * omega * h;
  return 2.0 * std::numbers::pi * h / std::acos(trace / (2.0 * std::sqrt(det)));
}

// Free oscillation along an eigenvector of K: frequency √(k/m)·√(1 − ζ²), amplitude ratio per period exp(−2πζ/√(1−ζ²)).
// The period may differ from the continuous one by the integrator's own error at the test's ω·dt (computed, not
// guessed) plus a margin of 0.1 % for reading zero crossings off samples; a 1 % error in the mass (0.5 % in the
// period) fails it.
TEST(Plant, FreeOscillationFrequencyAndDecay) {
  const Fixture f;
  const Vec2 p(0.222132, 0.03);
  for (double zeta : {0.0, 0.05, 0.2}) {
    PlantOptions o;
    o.tip_damping_ratio = zeta;
    o.servo_feels_load = false;  // the tip's own modes: a base that does not give way
    Plant plant = f.plant(o);
    const Vec2 q = f.q_at(p);
    plant.reset(q);
    Eigen::SelfAdjointEigenSolver<Mat2> eig(plant.stiffness(p));
    for (int mode = 0; mode < 2; ++mode) {
      const double k = eig.eigenvalues()(mode);
      const Vec2 dir = eig.eigenvectors().col(mode);
      PlantState s = plant.state();
      s.tip_m = p + 1e-4 * dir;
      s.tip_m_s.setZero();
      plant.set_state(s);
      const double dt = 5e-5;
      std::vector<double> t_up, peaks;  // upward zero crossings and positive peaks of the modal coordinate
      double prev = 1e-4, prev2 = 1e-4;
      for (int i = 1; i < 12000; ++i) {
        plant.step(hold(q), dt);
        const double x = (plant.state().tip_m - p).dot(dir);
        // Crossings count while the mode stands well above the rounding of the tip's position (≈ 1e-17 m).
        if (prev < 0 && x >= 0 && (peaks.empty() || peaks.back() > 1e-10)) t_up.push_back(i * dt - dt * x / (x - prev));
        if (prev > prev2 && prev >= x && prev > 0) peaks.push_back(prev);
        prev2 = prev;
        prev = x;
      }
      ASSERT_GE(t_up.size(), 4U);
      const double period = (t_up.back() - t_up.front()) / static_cast<double>(t_up.size() - 1);
      const double omega = std::sqrt(k / f.spec.moving_mass_kg);
      const double expected = 2 * std::numbers::pi / (omega * std::sqrt(1 - zeta * zeta));
      const double integrator = std::abs(symplectic_euler_period(omega, zeta, dt) - expected);
      EXPECT_NEAR(period, expected, integrator + 1e-3 * expected) << zeta << " mode " << mode;
      if (zeta > 0) {
        ASSERT_GE(peaks.size(), 3U);
        const double ratio = peaks[2] / peaks[1];
        EXPECT_NEAR(ratio, std::exp(-2 * std::numbers::pi * zeta / std::sqrt(1 - zeta * zeta)), 0.01) << zeta;
      }
    }
  }
}

TEST(Plant, EnergyDoesNotGrowWithoutDamping) {
  const Fixture f;
  PlantOptions o;
  o.tip_damping_ratio = 0.0;
  o.servo_feels_load = false;  // a loaded servo would drain energy through its velocity loop
  Plant plant = f.plant(o);
  const Vec2 p(0.2, -0.05), q = f.q_at(p);
  plant.reset(q);
  PlantState s = plant.state();
  s.tip_m = p + Vec2(1.5e-4, -0.7e-4);
  s.tip_m_s = Vec2(0.01, 0.02);
  plant.set_state(s);
  const double e0 = plant.relative_energy();
  double emax = e0, emin = e0;
  for (int i = 0; i < 40000; ++i) {  // 2 s, ~170 periods
    plant.step(hold(q), 5e-5);
    const double e = plant.relative_energy();
    emax = std::max(emax, e);
    emin = std::min(emin, e);
  }
  // Symplectic Euler: the energy oscillates by O(ωdt) but has no drift.
  EXPECT_LT(emax, e0 * 1.05);
  EXPECT_GT(emin, e0 * 0.95);
  EXPECT_NEAR(plant.relative_energy(), e0, 0.05 * e0);
}

// The drive is a P/P cascade: at equilibrium 0 = K_v·K_p·(q_ref − q) + Jᵀ·F, with K_v = 2ζ_sω_s·J_tune and
// K_p = ω_s/(2ζ_s), so q − q_ref = Jᵀ·F/(J_tune·ω_s²). For the thesis robot at the rectangle's centre
// (222.132, 0) mm JᵀJ has l² = 0.0225 m² on its diagonal, so J_tune = 0.01 + 3.6·0.0225 = 0.091 kg·m².
TEST(Plant, ConstantLoadGivesTheStaticJointErrorOfTheGains) {
  const Fixture f;
  const double j_tune = 0.01 + 3.6 * 0.150 * 0.150, omega = 2 * std::numbers::pi * 100.0;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> ux(0.18, 0.26), uy(-0.06, 0.06), uf(-150, 150);
  for (int trial = 0; trial < 4; ++trial) {
    const Vec2 p(ux(rng), uy(rng)), F(uf(rng), uf(rng));
    PlantOptions o;
    o.tip_damping_ratio = 0.5;
    Plant plant = f.plant(o);
    EXPECT_NEAR(plant.tuning_inertia().x(), j_tune, 1e-9);
    const Vec2 q = f.q_at(p);
    plant.reset(q);
    for (int i = 0; i < 8000; ++i) plant.step(hold(q), 5e-5, F);
    const Vec2 expected = f.spec.five_bar().jacobian(q).transpose() * F / (j_tune * omega * omega);
    const Vec2 got = plant.state().q_rad - q;
    EXPECT_GT(expected.norm(), 1e-5);  // a visible error: ~0.1 mrad per 100 N
    EXPECT_LT((got - expected).norm(), 2e-3 * expected.norm()) << trial;
  }
}

// Loaded, with feed-forward and the CG lever: a robot holding still stays exactly where it is.
TEST(Plant, LoadedServoAtRestStaysAtRest) {
  const Fixture f;
  for (const Vec2& p : {Vec2(0.2, 0.02), Vec2(0.26, -0.07)}) {
    Plant plant(f.spec.five_bar(), f.truth, 3.6, {}, f.truth);  // any lever: nothing is loaded
    const Vec2 q = f.q_at(p);
    plant.reset(q);
    for (int i = 0; i < 20000; ++i) plant.step(hold(q), 5e-5);
    EXPECT_LT((plant.state().tip_m - p).norm(), 1e-12);
    EXPECT_LT((plant.state().q_rad - q).norm(), 1e-14);
    EXPECT_LT(plant.state().qd_rad_s.norm(), 1e-14);
  }
}

TEST(Plant, RejectsBadOptions) {
  const Fixture f;
  PlantOptions o;
  o.step_rate_hz = 0;
  EXPECT_THROW(f.plant(o), Error);
  o = {};
  o.tip_damping_ratio = -0.1;
  EXPECT_THROW(f.plant(o), Error);
  o = {};
  o.motor_inertia_kg_m2 = 0.0;
  EXPECT_THROW(f.plant(o), Error);
  o = {};
  o.load_feedforward = -1.0;
  EXPECT_THROW(f.plant(o), Error);
  EXPECT_THROW(Plant(f.spec.five_bar(), nullptr, 3.6), Error);
  EXPECT_THROW(Plant(f.spec.five_bar(), f.truth, 0.0), Error);
}

}  // namespace
}  // namespace stiffpath::simulation
