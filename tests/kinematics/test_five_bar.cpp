// Property and hand-checked tests of the five-bar kinematics (eqs. 2.1–2.2), Jacobians and singularities.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/five_bar.hpp"

namespace stiffpath::kinematics {
namespace {

constexpr double kL = 0.150;
constexpr unsigned kSeed = 20261121;
constexpr int kSamples = 20000;

// A random point of the thesis workspace, x ∈ [172.132, 272.132] mm, y ∈ [−75, 75] mm.
Vec2 random_workspace_point(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ux(0.172132, 0.272132), uy(-0.075, 0.075);
  return {ux(rng), uy(rng)};
}

TEST(FiveBar, ForwardOfInverseIsIdentityOverTheWorkspace) {
  const FiveBar robot(kL);
  std::mt19937_64 rng(kSeed);
  double worst = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const Vec2 p = random_workspace_point(rng);
    const Vec2 q = robot.inverse(p);
    worst = std::max(worst, (robot.forward(q) - p).norm());
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(FiveBar, InverseOfForwardRecoversTheWorkingMode) {
  const FiveBar robot(kL);
  std::mt19937_64 rng(kSeed + 1);
  std::uniform_real_distribution<double> phi(-0.6, 0.6), eta(0.2, 1.2);
  for (int i = 0; i < kSamples; ++i) {
    const double f = phi(rng), e = eta(rng);
    const Vec2 q{f + e, f - e};
    const Vec2 back = robot.inverse(robot.forward(q));
    ASSERT_NEAR(back.x(), q.x(), 1e-10);
    ASSERT_NEAR(back.y(), q.y(), 1e-10);
  }
}

TEST(FiveBar, HandCheckedPointOnTheXAxis) {
  // On y = 0 the two arms are symmetric: θ1 = −θ2 = acos(x / 2l).
  const FiveBar robot(kL);
  const Vec2 q = robot.inverse({0.222132, 0.0});
  const double eta = std::acos(0.222132 / 0.3);
  EXPECT_NEAR(q.x(), eta, 1e-15);
  EXPECT_NEAR(q.y(), -eta, 1e-15);
  // Elbow A = l·e^{iθ1}; |AC| must equal l.
  const Vec2 a{kL * std::cos(q.x()), kL * std::sin(q.x())};
  EXPECT_NEAR((Vec2{0.222132, 0.0} - a).norm(), kL, 1e-15);
}

TEST(FiveBar, PassiveAnglesMatchEquation22) {
  const FiveBar robot(kL);
  const Vec2 p{0.2, 0.05};
  const Vec2 q = robot.inverse(p);
  const auto passive = robot.passive_angles(q);
  // θ3 = atan2(y − l sin θ1, x − l cos θ1), θ4 = atan2(y − l sin θ2, x − l cos θ2).
  EXPECT_NEAR(passive.theta3_rad, std::atan2(p.y() - kL * std::sin(q.x()), p.x() - kL * std::cos(q.x())), 1e-12);
  EXPECT_NEAR(passive.theta4_rad, std::atan2(p.y() - kL * std::sin(q.y()), p.x() - kL * std::cos(q.y())), 1e-12);
}

TEST(FiveBar, JacobianMatchesCentralDifferences) {
  const FiveBar robot(kL);
  std::mt19937_64 rng(kSeed + 2);
  const double h = 1e-6;
  for (int i = 0; i < 2000; ++i) {
    const Vec2 q = robot.inverse(random_workspace_point(rng));
    Mat2 numeric;
    for (int k = 0; k < 2; ++k) {
      Vec2 dq = Vec2::Zero();
      dq[k] = h;
      numeric.col(k) = (robot.forward(q + dq) - robot.forward(q - dq)) / (2 * h);
    }
    ASSERT_LT((robot.jacobian(q) - numeric).norm(), 1e-9);
  }
}

TEST(FiveBar, JacobianDotMatchesCentralDifferencesAlongAPath) {
  const FiveBar robot(kL);
  std::mt19937_64 rng(kSeed + 3);
  std::uniform_real_distribution<double> rate(-20.0, 20.0);
  const double h = 1e-6;
  for (int i = 0; i < 2000; ++i) {
    const Vec2 q = robot.inverse(random_workspace_point(rng));
    const Vec2 qd{rate(rng), rate(rng)};
    const Mat2 numeric = (robot.jacobian(q + h * qd) - robot.jacobian(q - h * qd)) / (2 * h);
    ASSERT_LT((robot.jacobian_dot(q, qd) - numeric).norm(), 1e-7);
  }
}

TEST(FiveBar, VelocityAndAccelerationLevelsRoundTrip) {
  const FiveBar robot(kL);
  std::mt19937_64 rng(kSeed + 4);
  std::uniform_real_distribution<double> v(-3.0, 3.0), a(-50.0, 50.0);
  for (int i = 0; i < kSamples; ++i) {
    const Vec2 q = robot.inverse(random_workspace_point(rng));
    const Vec2 pd{v(rng), v(rng)}, pdd{a(rng), a(rng)};
    const Vec2 qd = robot.joint_velocity(q, pd);
    const Vec2 qdd = robot.joint_acceleration(q, qd, pdd);
    ASSERT_LT((robot.velocity(q, qd) - pd).norm(), 1e-12);
    ASSERT_LT((robot.acceleration(q, qd, qdd) - pdd).norm(), 1e-10);
  }
}

TEST(FiveBar, AccelerationLevelMatchesSecondDifferenceOfForward) {
  // p(t) = f(q(t)) with q(t) = q0 + qd t + ½ qdd t²: p̈(0) from the contract vs from differences.
  const FiveBar robot(kL);
  const Vec2 q0 = robot.inverse({0.23, -0.04});
  const Vec2 qd{3.0, -5.0}, qdd{200.0, 150.0};
  const double h = 2e-5;  // truncation ~h²·p''''/12 and rounding ~ε·|p|/h² both stay below 1e-6 m/s²
  auto p = [&](double t) { return robot.forward(q0 + qd * t + 0.5 * qdd * t * t); };
  const Vec2 numeric = (p(h) - 2 * p(0) + p(-h)) / (h * h);
  EXPECT_LT((robot.acceleration(q0, qd, qdd) - numeric).norm(), 2e-6);
}

TEST(FiveBar, JacobianFromInverseAndJacobianDotFromJacobianMatchTheDirectForms) {
  const FiveBar robot(kL);
  std::mt19937_64 rng(kSeed + 7);
  std::uniform_real_distribution<double> rate(-20.0, 20.0);
  for (int i = 0; i < 2000; ++i) {
    InverseFrame frame;
    const InverseResult r = robot.solve_inverse(random_workspace_point(rng), frame);
    ASSERT_EQ(r.status, Reach::ok);
    ASSERT_LT((frame.jacobian - robot.jacobian(r.q)).norm(), 1e-15);
    const Vec2 qd{rate(rng), rate(rng)};
    ASSERT_LT((robot.jacobian_dot(frame, qd) - robot.jacobian_dot(r.q, qd)).norm(), 1e-13);
  }
}

TEST(FiveBar, RealTimeInverseAgreesWithCheckReachAndTheConditionAtTheRadius) {
  // solve_inverse(p, J) does the reach check itself; over the whole plane around the robot it must
  // refuse exactly what check_reach() refuses and report the same condition number.
  const FiveBar robot(kL);
  std::mt19937_64 rng(kSeed + 11);
  std::uniform_real_distribution<double> u(-0.32, 0.32);
  for (int i = 0; i < 20000; ++i) {
    const Vec2 p{u(rng), u(rng)};
    Mat2 J;
    const InverseResult r = robot.solve_inverse(p, J);
    ASSERT_EQ(r.status, robot.check_reach(p)) << p.transpose();
    if (r.status != Reach::ok) continue;
    const double c = p.norm() / (2 * kL), sn = std::sqrt(1 - c * c);  // κ = max(tan η, cot η)
    ASSERT_NEAR(r.condition_number, std::max(c / sn, sn / c), 1e-14 * r.condition_number);
    const double phi = std::atan2(p.y(), p.x()), eta = std::acos(p.norm() / (2 * kL));  // eq. 2.2
    ASSERT_LT((r.q - Vec2(phi + eta, phi - eta)).cwiseAbs().maxCoeff(), 1e-15);
  }
}

TEST(FiveBar, ClosedFormConditionNumberMatchesSvd) {
  const FiveBar robot(kL);
  std::mt19937_64 rng(kSeed + 5);
  for (int i = 0; i < 2000; ++i) {
    const Vec2 q = robot.inverse(random_workspace_point(rng));
    ASSERT_NEAR(robot.condition_number(q), robot.Mechanism::condition_number(q), 1e-9);
  }
}

TEST(FiveBar, ThesisGridIsReachableAndWellConditioned) {
  const FiveBar robot(kL);
  for (double x : {0.172132, 0.222132, 0.272132}) {
    for (double y : {-0.075, -0.0375, 0.0, 0.0375, 0.075}) {
      const InverseResult r = robot.solve_inverse({x, y});
      ASSERT_EQ(r.status, Reach::ok) << x << ", " << y;
      EXPECT_LT((robot.forward(r.q) - Vec2{x, y}).norm(), 1e-12);
      EXPECT_GT(r.condition_number, 1.0);
      EXPECT_LT(r.condition_number, 3.0);  // far corner (272.132, ±75) mm: cot(acos(r/2l)) = 2.78
    }
  }
}

TEST(FiveBar, RefusesStretchedOutAndOriginSingularities) {
  const FiveBar robot(kL, SingularityMargin{0.005, 8.0});
  EXPECT_EQ(robot.solve_inverse({0.300, 0.0}).status, Reach::near_stretched);
  EXPECT_EQ(robot.solve_inverse({0.296, 0.0}).status, Reach::near_stretched);  // within 5 mm of 2l
  EXPECT_EQ(robot.solve_inverse({0.0, 0.0}).status, Reach::near_origin);
  EXPECT_EQ(robot.solve_inverse({0.003, 0.001}).status, Reach::near_origin);
  EXPECT_EQ(robot.solve_inverse({0.5, 0.0}).status, Reach::near_stretched);
  EXPECT_EQ(robot.solve_inverse({std::nan(""), 0.0}).status, Reach::not_finite);
}

TEST(FiveBar, RefusesIllConditionedPointsAtTheDocumentedThreshold) {
  // κ = cot η for η < 45°; κ = 8 at η = atan(1/8), i.e. r = 2l·cos(atan(1/8)).
  const FiveBar robot(kL, SingularityMargin{0.0001, 8.0});
  const double r_limit = 2 * kL * std::cos(std::atan(1.0 / 8.0));
  EXPECT_EQ(robot.solve_inverse({r_limit - 1e-5, 0.0}).status, Reach::ok);
  EXPECT_EQ(robot.solve_inverse({r_limit + 1e-5, 0.0}).status, Reach::ill_conditioned);
  // Near the origin κ = tan η.
  const double r_inner = 2 * kL * std::cos(std::atan(8.0));
  EXPECT_EQ(robot.solve_inverse({r_inner + 1e-5, 0.0}).status, Reach::ok);
  EXPECT_EQ(robot.solve_inverse({r_inner - 1e-5, 0.0}).status, Reach::ill_conditioned);
}

TEST(FiveBar, RefusalNamesThePointAndTheReason) {
  const FiveBar robot(kL);
  try {
    (void)robot.inverse({0.299, 0.001});
    FAIL() << "expected a refusal";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("299.0000 mm"), std::string::npos) << what;
    EXPECT_NE(what.find("stretched"), std::string::npos) << what;
  }
}

TEST(FiveBar, SolveInverseNeverReturnsNaN) {
  const FiveBar robot(kL);
  std::mt19937_64 rng(kSeed + 6);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  for (int i = 0; i < kSamples; ++i) {
    const InverseResult r = robot.solve_inverse({u(rng), u(rng)});
    ASSERT_TRUE(std::isfinite(r.q.x()) && std::isfinite(r.q.y()));
  }
}

TEST(FiveBar, RejectsBadConstruction) {
  EXPECT_THROW(FiveBar(0.0), Error);
  EXPECT_THROW(FiveBar(-0.1), Error);
  EXPECT_THROW(FiveBar(0.15, SingularityMargin{0.2, 8.0}), Error);
  EXPECT_THROW(FiveBar(0.15, SingularityMargin{0.001, 0.5}), Error);
}

}  // namespace
}  // namespace stiffpath::kinematics
