// Tests of ISO 9283 cornering round-off and overshoot on hand-built commanded and attained paths.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/cornering.hpp"

namespace stiffpath::evaluation {
namespace {

// Points from a to b, `n` intervals, spaced like a move that starts and stops at rest (dense at both ends).
void append_move(std::vector<Point2>& out, const Point2& a, const Point2& b, int n) {
  for (int i = out.empty() ? 0 : 1; i <= n; ++i) {
    const double s = static_cast<double>(i) / n;
    const double eased = s * s * (3.0 - 2.0 * s);
    out.push_back(a + eased * (b - a));
  }
}

std::vector<Point2> l_shape() {
  std::vector<Point2> path;
  append_move(path, {0.0, 0.0}, {0.1, 0.0}, 400);
  append_move(path, {0.1, 0.0}, {0.1, 0.1}, 400);
  return path;
}

TEST(Cornering, ExactPathHasNoDeviationAndOneRightAngle) {
  const auto command = l_shape();
  const auto c = iso9283_cornering(command, command);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].turn_rad, std::numbers::pi / 2, 1e-9);
  EXPECT_NEAR(c[0].corner.x(), 0.1, 1e-9);
  EXPECT_NEAR(c[0].corner.y(), 0.0, 1e-9);
  EXPECT_LT(c[0].round_off_m, 1e-12);
  EXPECT_LT(c[0].overshoot_m, 1e-12);
}

TEST(Cornering, OvershootPastTheCornerIsMeasuredOnInertiasSide) {
  const auto command = l_shape();
  std::vector<Point2> attained;
  append_move(attained, {0.0, 0.0}, {0.1, 0.0}, 200);
  attained.push_back({0.102, 0.0005});  // carried on along +x by 2 mm, then back to the new side
  attained.push_back({0.1005, 0.002});
  append_move(attained, {0.1, 0.004}, {0.1, 0.1}, 200);
  const auto c = iso9283_cornering(command, attained);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].overshoot_m, 0.002, 1e-12);
  EXPECT_LT(c[0].round_off_m, 1e-12);  // it passed through the corner
}

TEST(Cornering, RoundedCornerIsRoundOffNotOvershoot) {
  const auto command = l_shape();
  const double r = 0.005;
  std::vector<Point2> attained;
  append_move(attained, {0.0, 0.0}, {0.1 - r, 0.0}, 200);
  for (int i = 1; i <= 90; ++i) {  // quarter circle centred at (0.1 − r, r)
    const double a = -std::numbers::pi / 2 + i * std::numbers::pi / 180.0;
    attained.push_back({0.1 - r + r * std::cos(a), r + r * std::sin(a)});
  }
  append_move(attained, {0.1, r}, {0.1, 0.1}, 200);
  const auto c = iso9283_cornering(command, attained);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].round_off_m, r * (std::sqrt(2.0) - 1.0), 1e-6);  // chords of 1° sag below 0.2 µm
  EXPECT_LT(c[0].overshoot_m, 1e-12);
}

TEST(Cornering, ClosedTriangleHasTwoInteriorCornersInOrder) {
  const Point2 a{0.0, 0.0}, b{0.1, 0.0}, t{0.05, 0.0866};
  std::vector<Point2> command;
  append_move(command, a, b, 300);
  append_move(command, b, t, 300);
  append_move(command, t, a, 300);
  const auto c = iso9283_cornering(command, command);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR((c[0].corner - b).norm(), 0.0, 1e-9);
  EXPECT_NEAR((c[1].corner - t).norm(), 0.0, 1e-9);
  for (const auto& corner : c) EXPECT_NEAR(corner.turn_rad, 2.0 * std::numbers::pi / 3, 1e-3);
}

TEST(Cornering, StraightOrGentlyCurvedCommandHasNoCorners) {
  std::vector<Point2> line;
  append_move(line, {0.0, 0.0}, {0.1, 0.05}, 500);
  EXPECT_TRUE(iso9283_cornering(line, line).empty());
  std::vector<Point2> arc;  // radius 20 mm: each 1 µm chord turns far less than 10°
  for (int i = 0; i <= 2000; ++i) {
    const double a = i * std::numbers::pi / 2000;
    arc.push_back({0.02 * std::cos(a), 0.02 * std::sin(a)});
  }
  EXPECT_TRUE(iso9283_cornering(arc, arc).empty());
}

// An L whose corner is replaced by a quarter circle of radius r (centre inside the corner).
std::vector<Point2> rounded_l(double r) {
  std::vector<Point2> path;
  append_move(path, {0.0, 0.0}, {0.1 - r, 0.0}, 400);
  for (int i = 1; i < 90; ++i) {
    const double a = -std::numbers::pi / 2 + i * std::numbers::pi / 180.0;
    path.push_back({0.1 - r + r * std::cos(a), r + r * std::sin(a)});
  }
  append_move(path, {0.1, r}, {0.1, 0.1}, 400);
  return path;
}

// A smoothed reference cuts an exact-stop corner by a few µm over a few tens of µm (8 ms of moving
// averages at 5 g: ~9 µm over ±70 µm): still one corner, where its sides meet, and the cut is round-off.
TEST(Cornering, CornerRoundedByAFewMicrometresIsStillOneCorner) {
  const double r = 20e-6;
  const auto command = rounded_l(r);
  const auto c = iso9283_cornering(command, command);
  ASSERT_EQ(c.size(), 1u);
  // The command's vertices are found in one pass (VertexFinder, 1 µm merge distance): the last vertex
  // on the fillet can lie up to the merge distance plus one sample (1° of arc) before the tangent point,
  // (1 µm + rπ/180)²/(2r) = 46 nm off that side's line, and the corner with it (a whole-path
  // Ramer–Douglas–Peucker happened to pick the tangent points exactly).
  const double bound = std::pow(1e-6 + r * std::numbers::pi / 180, 2) / (2 * r);
  EXPECT_NEAR(c[0].corner.x(), 0.1, bound);
  EXPECT_NEAR(c[0].corner.y(), 0.0, bound);
  EXPECT_NEAR(c[0].turn_rad, std::numbers::pi / 2, 1e-6);
  EXPECT_NEAR(c[0].round_off_m, r * (std::sqrt(2.0) - 1.0), 0.05e-6);
  EXPECT_LT(c[0].overshoot_m, bound);
  // The sharp L attained against that command: it passes through the sides' intersection.
  const auto sharp = iso9283_cornering(command, l_shape());
  ASSERT_EQ(sharp.size(), 1u);
  EXPECT_LT(sharp[0].round_off_m, bound);  // the corner's own error, as above
}

// A fillet wider than the corner span turns gradually: no corner, and no piece of it becomes one.
TEST(Cornering, FilletWiderThanTheCornerSpanIsNoCorner) {
  for (double r : {2e-3, 0.6e-3}) {
    const auto command = rounded_l(r);
    EXPECT_TRUE(iso9283_cornering(command, command).empty()) << r;
  }
}

TEST(Cornering, MissedCornerHasItsDistanceAndNoOvershoot) {
  const auto command = l_shape();
  const std::vector<Point2> elsewhere{{0.5, 0.5}, {0.6, 0.5}};  // far from the corner at (0.1, 0)
  const auto c = iso9283_cornering(command, elsewhere);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_FALSE(c[0].reached);
  EXPECT_NEAR(c[0].round_off_m, std::hypot(0.4, 0.5), 1e-12);
  EXPECT_EQ(c[0].overshoot_m, 0.0);
  EXPECT_TRUE(iso9283_cornering(command, command)[0].reached);
}

TEST(Cornering, RefusesUnusableInput) {
  const auto command = l_shape();
  EXPECT_THROW(iso9283_cornering(command, std::vector<Point2>{{0.1, 0.0}}), Error);
  EXPECT_THROW(iso9283_cornering(std::vector<Point2>{{0.0, 0.0}}, command), Error);
  auto broken = command;
  broken[10].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(iso9283_cornering(command, broken), Error);
  EXPECT_THROW(iso9283_cornering(broken, command), Error);
}

}  // namespace
}  // namespace stiffpath::evaluation
