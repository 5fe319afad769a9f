// The least-squares helper against closed forms: linear least squares, its covariance, gauge freedoms, bounds.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <random>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/least_squares.hpp"

namespace stiffpath::core {
namespace {

// y = a·exp(−b·t) + c sampled at 40 times with Gaussian noise σ.
struct Decay {
  Eigen::VectorXd t, y;
  double sigma;
  Decay(const Eigen::Vector3d& truth, double sigma_, unsigned seed) : t(40), y(40), sigma(sigma_) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0.0, sigma);
    for (int i = 0; i < 40; ++i) {
      t(i) = 0.1 * i;
      y(i) = truth(0) * std::exp(-truth(1) * t(i)) + truth(2) + noise(rng);
    }
  }
  LeastSquaresProblem problem() const {
    LeastSquaresProblem p;
    p.residuals = [this](const Eigen::VectorXd& x) {
      return Eigen::VectorXd((x(0) * (-x(1) * t.array()).exp() + x(2) - y.array()).matrix());
    };
    return p;
  }
};

TEST(LeastSquares, ALinearProblemGivesTheNormalEquationsSolutionAndItsCovariance) {
  // r = A·x − b: the minimum is A⁺b and the covariance σ̂²(AᵀA)⁻¹ with σ̂² = Σr²/(m − n), in closed form.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixXd A(30, 4);
  Eigen::VectorXd b(30);
  for (int i = 0; i < 30; ++i) {
    for (int j = 0; j < 4; ++j) A(i, j) = g(rng);
    b(i) = g(rng);
  }
  LeastSquaresProblem p;
  p.residuals = [&](const Eigen::VectorXd& x) { return Eigen::VectorXd(A * x - b); };
  p.jacobian = [&](const Eigen::VectorXd&, const Eigen::VectorXd&) { return A; };
  const LeastSquaresResult res = least_squares(p, Eigen::VectorXd::Zero(4));
  const Eigen::VectorXd want = A.colPivHouseholderQr().solve(b);
  EXPECT_LT((res.x - want).norm(), 1e-9 * want.norm());
  ASSERT_TRUE(res.statistics);
  const double s2 = (A * want - b).squaredNorm() / 26.0;
  const Eigen::MatrixXd cov = s2 * (A.transpose() * A).inverse();
  EXPECT_LT((res.statistics->covariance - cov).norm(), 1e-8 * cov.norm());
  EXPECT_EQ(res.statistics->rank, 4);
  EXPECT_EQ(res.statistics->degrees_of_freedom, 26);
  EXPECT_TRUE(res.statistics->undetermined().empty());
  EXPECT_EQ(res.stop, LeastSquaresStop::converged);
  // With a given noise the covariance is σ²(AᵀA)⁻¹.
  const LeastSquaresResult given = least_squares(p, Eigen::VectorXd::Zero(4), {}, 0.5);
  EXPECT_LT((given.statistics->covariance - 0.25 * (A.transpose() * A).inverse()).norm(), 1e-8 * cov.norm());
  EXPECT_FALSE(given.statistics->sigma_estimated);
}

TEST(LeastSquares, StatedUncertaintiesCoverTheTruthAsOftenAsTheyShould) {
  // A nonlinear fit from 200 noisy data sets: each parameter within 1.96 stated σ of the truth about 95 % of the time.
  const Eigen::Vector3d truth(2.0, 0.7, 0.5);
  int inside[3] = {0, 0, 0};
  constexpr int kSets = 200;
  for (int seed = 0; seed < kSets; ++seed) {
    const Decay d(truth, 0.02, static_cast<unsigned>(seed));
    const LeastSquaresResult r = least_squares(d.problem(), Eigen::Vector3d(1.0, 1.0, 0.0));
    ASSERT_TRUE(r.statistics);
    const Eigen::VectorXd se = r.statistics->standard_errors();
    for (int k = 0; k < 3; ++k) inside[k] += std::abs(r.x(k) - truth(k)) <= 1.96 * se(k) ? 1 : 0;
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_GE(inside[k], kSets * 90 / 100) << k;
    EXPECT_LE(inside[k], kSets * 99 / 100) << k;
  }
}

TEST(LeastSquares, FiniteDifferencesAndAnAnalyticJacobianReachTheSameMinimum) {
  const Decay d(Eigen::Vector3d(2.0, 0.7, 0.5), 0.02, 3);
  LeastSquaresProblem analytic = d.problem();
  analytic.jacobian = [&](const Eigen::VectorXd& x, const Eigen::VectorXd&) {
    Eigen::MatrixXd J(d.t.size(), 3);
    for (Eigen::Index i = 0; i < d.t.size(); ++i) {
      const double e = std::exp(-x(1) * d.t(i));
      J.row(i) << e, -x(0) * d.t(i) * e, 1.0;
    }
    return J;
  };
  const auto fd = least_squares(d.problem(), Eigen::Vector3d(1.0, 1.0, 0.0));
  const auto an = least_squares(analytic, Eigen::Vector3d(1.0, 1.0, 0.0));
  EXPECT_LT((fd.x - an.x).norm(), 1e-6);
  EXPECT_NEAR(fd.cost, an.cost, 1e-9 * an.cost);
}

TEST(LeastSquares, ARunContinuedIsTheSameAsOneUninterruptedRun) {
  const Decay d(Eigen::Vector3d(2.0, 0.7, 0.5), 0.02, 5);
  LevenbergMarquardt whole(d.problem(), Eigen::Vector3d(5.0, 3.0, -1.0)), parts(d.problem(), Eigen::Vector3d(5.0, 3.0, -1.0));
  whole.run(30);
  parts.run(2);
  parts.run(28);
  EXPECT_EQ(whole.x(), parts.x());  // bit for bit
  EXPECT_EQ(whole.cost(), parts.cost());
}

TEST(LeastSquares, ParametersSeenOnlyAsASumAreReportedUndeterminedAndFixedInTheOrderAsked) {
  // r depends on a + b only (a gauge freedom, like an instrument's rotation against a common joint offset).
  LeastSquaresProblem p;
  p.residuals = [](const Eigen::VectorXd& x) {
    Eigen::VectorXd r(3);
    r << x(0) + x(1) - 3.0, 2.0 * (x(0) + x(1)) - 6.1, x(2) - 1.0;
    return r;
  };
  const auto res = least_squares(p, Eigen::Vector3d(0.0, 0.0, 0.0));
  ASSERT_TRUE(res.statistics);
  EXPECT_EQ(res.statistics->rank, 2);
  const auto dirs = res.statistics->undetermined();
  ASSERT_EQ(dirs.size(), 1u);
  EXPECT_NEAR(std::abs(dirs[0](0)), std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(dirs[0](0), -dirs[0](1), 1e-6);
  EXPECT_NEAR(dirs[0](2), 0.0, 1e-6);
  EXPECT_NEAR(res.x(0) + res.x(1), (3.0 + 2.0 * 6.1) / 5.0, 1e-6);  // the sum is determined: (1·3 + 2·6.1)/(1 + 4)
  const Eigen::MatrixXd& J = res.statistics->jacobian;
  EXPECT_EQ(parameters_to_fix(J, 1e-6), std::vector<int>{0});
  const int prefer_b[] = {1};
  EXPECT_EQ(parameters_to_fix(J, 1e-6, prefer_b), std::vector<int>{1});
  const int prefer_c[] = {2, 1};  // c is determined: fixing it would lose rank, so b is fixed instead
  EXPECT_EQ(parameters_to_fix(J, 1e-6, prefer_c), std::vector<int>{1});
  // Fixed, the other is determined and keeps its start.
  p.fixed = {false, true, false};
  const auto held = least_squares(p, Eigen::Vector3d(0.0, 0.25, 0.0));
  EXPECT_EQ(held.x(1), 0.25);
  EXPECT_NEAR(held.x(0), 3.04 - 0.25, 1e-6);
  EXPECT_EQ(held.statistics->rank, 2);
  EXPECT_EQ(held.statistics->covariance(1, 1), 0.0);
  EXPECT_GT(held.statistics->covariance(0, 0), 0.0);
}

TEST(LeastSquares, BoundsHoldAndAreReported) {
  LeastSquaresProblem p;
  p.residuals = [](const Eigen::VectorXd& x) {
    Eigen::VectorXd r(2);
    r << x(0) - 2.0, x(1) + 1.0;
    return r;
  };
  p.lower = Eigen::Vector2d(-10.0, 0.0);
  p.upper = Eigen::Vector2d(1.5, 10.0);
  const auto res = least_squares(p, Eigen::Vector2d(0.0, 5.0));
  EXPECT_DOUBLE_EQ(res.x(0), 1.5);
  EXPECT_DOUBLE_EQ(res.x(1), 0.0);
  EXPECT_TRUE(res.at_bound[0]);
  EXPECT_TRUE(res.at_bound[1]);
}

TEST(LeastSquares, ScaleSetsTheUnitOfTheIdentifiabilityAnalysis) {
  // Two parameters whose effects differ by 10⁸: with unit scales the weak one counts as undetermined, with a
  // scale that makes them comparable it is determined.
  LeastSquaresProblem p;
  p.residuals = [](const Eigen::VectorXd& x) {
    Eigen::VectorXd r(2);
    r << x(0) - 1.0, 1e-8 * x(1) - 1e-8;
    return r;
  };
  EXPECT_EQ(least_squares(p, Eigen::Vector2d::Zero()).statistics->rank, 1);
  p.scale = Eigen::Vector2d(1.0, 1e8);
  const auto scaled = least_squares(p, Eigen::Vector2d::Zero());
  EXPECT_EQ(scaled.statistics->rank, 2);
  EXPECT_NEAR(scaled.x(1), 1.0, 1e-6);
}

TEST(LeastSquares, MismatchedInputsAreRefused) {
  LeastSquaresProblem p;
  p.residuals = [](const Eigen::VectorXd& x) { return x; };
  p.lower = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(LevenbergMarquardt(p, Eigen::Vector2d::Zero()), Error);
  p.lower.resize(0);
  p.scale = Eigen::Vector2d(1.0, 0.0);
  EXPECT_THROW(LevenbergMarquardt(p, Eigen::Vector2d::Zero()), Error);
  p.scale.resize(0);
  EXPECT_THROW(LevenbergMarquardt(p, Eigen::Vector2d(NAN, 0.0)), Error);
}

}  // namespace
}  // namespace stiffpath::core
