// Tests of the total-least-squares line fit against an eigen-decomposition, hand-checked cases and seeded sweeps.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <random>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/line_fit.hpp"

namespace stiffpath::evaluation {
namespace {

TEST(LineFit, HandCheckedDiagonalAndRectangle) {
  const std::vector<Point2> diagonal{{0, 0}, {1, 1}, {2, 2}};
  const LineFit d = fit_line_tls(diagonal);
  EXPECT_NEAR(d.line.direction.x(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(d.line.direction.y(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(d.rms_residual_m, 0.0, 1e-15);
  // Corners of a 2 × 0.2 rectangle: the axis is x, every point is 0.1 from it.
  const std::vector<Point2> box{{-1, -0.1}, {1, -0.1}, {1, 0.1}, {-1, 0.1}};
  const LineFit b = fit_line_tls(box);
  EXPECT_NEAR(std::abs(b.line.direction.x()), 1.0, 1e-15);
  EXPECT_NEAR(b.rms_residual_m, 0.1, 1e-15);
  EXPECT_NEAR(b.spread_m, 1.0, 1e-15);
}

TEST(LineFit, MatchesTheScatterMatrixEigenvectorOnRandomClouds) {
  std::mt19937_64 rng(91);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi), along(-0.05, 0.05);
  for (int trial = 0; trial < 200; ++trial) {
    const double a = angle(rng), sigma = 1e-4 * (1 + trial % 7);
    const Point2 dir{std::cos(a), std::sin(a)}, nrm{-dir.y(), dir.x()}, origin{noise(rng), noise(rng)};
    std::vector<Point2> pts;
    std::vector<double> w;
    for (int i = 0; i < 50; ++i) {
      pts.push_back(origin + along(rng) * dir + sigma * noise(rng) * nrm);
      w.push_back(0.5 + (i % 3));
    }
    const LineFit fit = fit_line_tls(pts, w);
    Point2 c{0, 0};
    double sw = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) c += w[i] * pts[i], sw += w[i];
    c /= sw;
    Eigen::Matrix2d s = Eigen::Matrix2d::Zero();
    for (std::size_t i = 0; i < pts.size(); ++i) s += w[i] * (pts[i] - c) * (pts[i] - c).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(s);
    const Point2 major = eig.eigenvectors().col(1);
    EXPECT_NEAR(std::abs(fit.line.direction.dot(major)), 1.0, 1e-12);
    EXPECT_NEAR(fit.rms_residual_m, std::sqrt(eig.eigenvalues()(0) / sw), 1e-12);
    EXPECT_LT((fit.line.origin - c).norm(), 1e-12);
    // Direction points from the first towards the last point.
    EXPECT_GE(fit.line.direction.dot(pts.back() - pts.front()), 0.0);
  }
}

TEST(LineFit, FrameOfTheLine) {
  const Line2 line{{1.0, 2.0}, {0.6, 0.8}};
  const Point2 p = line.at(3.0, -0.5);
  EXPECT_NEAR(line.along(p), 3.0, 1e-15);
  EXPECT_NEAR(line.offset(p), -0.5, 1e-15);
  EXPECT_NEAR(line.normal().x(), -0.8, 1e-15);
}

TEST(LineFit, IntersectionAndAngle) {
  const Line2 a{{0, 0}, {1, 0}}, b{{2, -1}, Point2{1, 1}.normalized()};
  const auto x = intersect(a, b);
  ASSERT_TRUE(x.has_value());
  EXPECT_NEAR(x->x(), 3.0, 1e-15);
  EXPECT_NEAR(x->y(), 0.0, 1e-15);
  EXPECT_FALSE(intersect(a, Line2{{0, 1}, {-1, 0}}).has_value());
  EXPECT_NEAR(angle_between({1, 0}, {-1, 0}), std::numbers::pi, 1e-15);
  EXPECT_NEAR(angle_between({1, 0}, {0.5, std::sqrt(3) / 2}), std::numbers::pi / 3, 1e-15);
}

TEST(LineFit, RejectsDegenerateInput) {
  const std::vector<Point2> one{{1, 1}}, same{{1, 1}, {1, 1}}, nan{{0, 0}, {std::nan(""), 1}};
  EXPECT_THROW(fit_line_tls(one), Error);
  EXPECT_THROW(fit_line_tls(same), Error);
  EXPECT_THROW(fit_line_tls(nan), Error);
  const std::vector<Point2> two{{0, 0}, {1, 0}};
  const std::vector<double> negative{1.0, -1.0};
  EXPECT_THROW(fit_line_tls(two, negative), Error);
}

}  // namespace
}  // namespace stiffpath::evaluation
