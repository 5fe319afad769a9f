// Tests of the smoothing spline: a dense reference solve, its filter response, exact |f| integrals, lines kept.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <random>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/smoothing_spline.hpp"

namespace stiffpath::evaluation {
namespace {

constexpr double kPi = std::numbers::pi;

// Evenly spaced samples of y(t) on [0, length].
void sample(double length, std::size_t n, double (*y)(double), std::vector<double>& t, std::vector<double>& v) {
  t.resize(n);
  v.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    t[i] = length * static_cast<double>(i) / static_cast<double>(n - 1);
    v[i] = y(t[i]);
  }
}

TEST(SmoothingSpline, MatchesADenseSolveOfThePenalisedProblem) {
  // Green & Silverman (2.4): minimiser g = (W + α Q R⁻¹ Qᵀ)⁻¹ W y, built densely here.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> gap(0.5e-3, 2e-3), val(-1e-4, 1e-4), wt(0.5, 2.0);
  const int n = 14;
  std::vector<double> t(n), y(n), w(n);
  double s = 0;
  for (int i = 0; i < n; ++i) t[i] = (s += gap(rng)), y[i] = val(rng), w[i] = wt(rng);
  const double cutoff = 4e-3;
  const SmoothingSpline spline = SmoothingSpline::fit(t, y, cutoff, w);
  const double alpha = spline.penalty();
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(n, n - 2), R = Eigen::MatrixXd::Zero(n - 2, n - 2);
  for (int k = 1; k < n - 1; ++k) {
    const double h0 = t[k] - t[k - 1], h1 = t[k + 1] - t[k];
    Q(k - 1, k - 1) = 1 / h0;
    Q(k, k - 1) = -1 / h0 - 1 / h1;
    Q(k + 1, k - 1) = 1 / h1;
    R(k - 1, k - 1) = (h0 + h1) / 3;
    if (k < n - 2) R(k - 1, k) = R(k, k - 1) = h1 / 6;
  }
  Eigen::VectorXd Y = Eigen::Map<Eigen::VectorXd>(y.data(), n);
  Eigen::MatrixXd W = Eigen::VectorXd::Map(w.data(), n).asDiagonal();
  const Eigen::VectorXd g = (W + alpha * Q * R.inverse() * Q.transpose()).ldlt().solve(W * Y);
  for (int i = 0; i < n; ++i) EXPECT_NEAR(spline.value(t[i]), g(i), 1e-12) << i;
  EXPECT_GT(alpha, 0.0);
}

TEST(SmoothingSpline, ActsAsTheDocumentedLowPassFilter) {
  // 20 µm spacing like a 1200 dpi scan; wiggles of wavelength λ keep 1 / (1 + (L_c/λ)⁴) of their amplitude.
  const double cutoff = 1e-3, length = 0.06;
  for (const double lambda : {cutoff / 2, cutoff, 2 * cutoff, 4 * cutoff}) {
    std::vector<double> t, y;
    const std::size_t n = 3001;
    t.resize(n);
    y.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      t[i] = length * static_cast<double>(i) / (n - 1);
      y[i] = std::sin(2 * kPi * t[i] / lambda);
    }
    const SmoothingSpline spline = SmoothingSpline::fit(t, y, cutoff);
    // Amplitude by projection on the sine over the middle (away from the ends).
    double num = 0, den = 0;
    for (std::size_t i = n / 4; i < 3 * n / 4; ++i) {
      const double ref = std::sin(2 * kPi * t[i] / lambda);
      num += spline.value(t[i]) * ref;
      den += ref * ref;
    }
    const double expected = 1.0 / (1.0 + std::pow(cutoff / lambda, 4));
    EXPECT_NEAR(num / den, expected, 0.02) << "wavelength " << lambda;
  }
}

TEST(SmoothingSpline, KeepsStraightLinesWhateverThePenalty) {
  std::vector<double> t, y;
  sample(0.1, 500, [](double x) { return 3e-3 - 0.02 * x; }, t, y);
  for (const double cutoff : {0.0, 1e-3, 1.0}) {
    const SmoothingSpline spline = SmoothingSpline::fit(t, y, cutoff);
    for (double x = 0; x <= 0.1; x += 0.0037) EXPECT_NEAR(spline.value(x), 3e-3 - 0.02 * x, 1e-13);
    EXPECT_NEAR(spline.slope(0.05), -0.02, 1e-10);
  }
}

TEST(SmoothingSpline, InterpolatesAndIntegratesTheAbsoluteValueExactly) {
  std::vector<double> t, y;
  sample(2 * kPi, 4001, [](double x) { return std::sin(x); }, t, y);
  const SmoothingSpline spline = SmoothingSpline::fit(t, y, 0.0);
  for (std::size_t i = 0; i < t.size(); i += 97) EXPECT_NEAR(spline.value(t[i]), y[i], 1e-14);
  EXPECT_NEAR(spline.integral_abs(0, 2 * kPi), 4.0, 1e-9);
  EXPECT_NEAR(spline.integral_abs(kPi / 2, 3 * kPi / 2), 2.0, 1e-9);
  const auto ex = spline.extremes(0, 2 * kPi);
  EXPECT_NEAR(ex.max, 1.0, 1e-9);
  EXPECT_NEAR(ex.min, -1.0, 1e-9);
  EXPECT_NEAR(ex.max_abs, 1.0, 1e-9);
  EXPECT_NEAR(std::abs(std::sin(ex.t_at_max_abs)), 1.0, 1e-9);
}

TEST(SmoothingSpline, IntegralOfASignChangingCubicAgreesWithFineQuadrature) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> v(-1, 1);
  std::vector<double> t(40), y(40);
  for (int i = 0; i < 40; ++i) t[i] = 0.1 * i, y[i] = v(rng);
  const SmoothingSpline spline = SmoothingSpline::fit(t, y, 0.3);
  double reference = 0;
  const int steps = 400000;
  const double a = 0.05, b = 3.83, h = (b - a) / steps;
  for (int k = 0; k < steps; ++k) reference += std::abs(spline.value(a + (k + 0.5) * h)) * h;
  EXPECT_NEAR(spline.integral_abs(a, b), reference, 1e-8);
}

TEST(SmoothingSpline, MergesRepeatedParametersAndSortsInput) {
  const std::vector<double> t{0.3, 0.1, 0.2, 0.2, 0.0}, y{3, 1, 1, 3, 0};
  const SmoothingSpline spline = SmoothingSpline::fit(t, y, 0.0);
  EXPECT_EQ(spline.size(), 4u);
  EXPECT_NEAR(spline.value(0.2), 2.0, 1e-12);
  EXPECT_NEAR(spline.value(0.3), 3.0, 1e-12);
}

TEST(SmoothingSpline, RejectsBadInput) {
  const std::vector<double> t{0, 1, 2}, y{0, std::nan(""), 1}, ok{0, 1, 2}, w{1, 0, 1};
  EXPECT_THROW(SmoothingSpline::fit(t, y, 1.0), Error);
  EXPECT_THROW(SmoothingSpline::fit(t, ok, -1.0), Error);
  EXPECT_THROW(SmoothingSpline::fit(t, ok, 1.0, w), Error);
  EXPECT_THROW(SmoothingSpline::fit(std::vector<double>{}, std::vector<double>{}, 1.0), Error);
}

}  // namespace
}  // namespace stiffpath::evaluation
