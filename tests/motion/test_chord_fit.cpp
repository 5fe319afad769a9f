// Chord fitting under G64: biarcs by construction, and fitted chains checked against the curve they were cut from.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "stiffpath/motion/biarc.hpp"
#include "stiffpath/motion/chord_fit.hpp"
#include "stiffpath/motion/junction.hpp"

namespace stiffpath::motion {
namespace {

Vec2 unit(double angle_rad) { return {std::cos(angle_rad), std::sin(angle_rad)}; }

// Hands out prepared segments.
class ListSource final : public PathSource {
 public:
  explicit ListSource(std::vector<PathSegment> segments) : segments_(std::move(segments)) {}
  std::optional<PathSegment> next() override {
    if (next_ == segments_.size()) return std::nullopt;
    return segments_[next_++];
  }

 private:
  std::vector<PathSegment> segments_;
  std::size_t next_ = 0;
};

// G64 P`tolerance_m` lines through `points`, laser on, line numbers 10, 11, …
std::vector<PathSegment> chords(const std::vector<Vec2>& points, double tolerance_m) {
  std::vector<PathSegment> out;
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    PathSegment s = make_line(points[k], points[k + 1]);
    s.mode = JunctionMode::blend;
    s.blend_tolerance_m = tolerance_m;
    s.laser_on = true;
    s.power = 0.5;
    s.feed_m_s = 0.2;
    s.line = 10 + static_cast<int>(k);
    out.push_back(s);
  }
  return out;
}

std::vector<PathSegment> fitted(const std::vector<PathSegment>& input) {
  ListSource source(input);
  ChordFitter fitter(source);
  std::vector<PathSegment> out;
  while (auto s = fitter.next()) out.push_back(*s);
  return out;
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double u = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + u * d - p).norm();
}

// Each piece lies within `tolerance_m` of the chord whose source line it carries (at 33 points),
// pieces meet exactly and tangentially, and the whole starts and ends where the chords do.
void expect_fits(const std::vector<PathSegment>& input, const std::vector<PathSegment>& output, double tolerance_m) {
  ASSERT_FALSE(output.empty());
  EXPECT_EQ(output.front().start_m, input.front().start_m);
  EXPECT_EQ(output.back().end_m, input.back().end_m);
  for (std::size_t k = 0; k < output.size(); ++k) {
    const PathSegment& piece = output[k];
    ASSERT_GT(piece.length_m, 0.0) << "piece " << k;
    const PathSegment& chord = input.at(static_cast<std::size_t>(piece.line - input.front().line));
    EXPECT_EQ(piece.feed_m_s, chord.feed_m_s);
    EXPECT_EQ(piece.laser_on, chord.laser_on);
    EXPECT_EQ(piece.power, chord.power);
    for (int m = 0; m <= 32; ++m) {
      const Vec2 p = point_at(piece, piece.length_m * m / 32).position_m;
      ASSERT_LE(distance_to_segment(p, chord.start_m, chord.end_m), tolerance_m * (1 + 1e-9))
          << "piece " << k << " of line " << piece.line;
    }
    if (k + 1 < output.size()) {
      ASSERT_EQ(piece.end_m, output[k + 1].start_m) << "piece " << k;
    }
  }
}

TEST(Biarc, JoinsBothTangentsThroughOneTangentJoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-0.6, 0.6), length(1e-5, 1e-2);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec2 p0(0.2, -0.1);
    const double heading = 3.0 * angle(rng);
    const Vec2 p1 = p0 + length(rng) * unit(heading);
    const Vec2 t0 = unit(heading + angle(rng)), t1 = unit(heading + angle(rng));
    const auto pieces = biarc(p0, t0, p1, t1);
    ASSERT_TRUE(pieces.has_value()) << "trial " << trial;
    const auto& [first, second] = *pieces;
    EXPECT_EQ(first.start_m, p0);
    EXPECT_EQ(first.end_m, second.start_m);
    EXPECT_EQ(second.end_m, p1);
    EXPECT_LT(turn_angle_rad(start_tangent(first), t0), 1e-9) << "trial " << trial;
    EXPECT_LT(turn_angle_rad(end_tangent(first), start_tangent(second)), 1e-9) << "trial " << trial;
    EXPECT_LT(turn_angle_rad(end_tangent(second), t1), 1e-9) << "trial " << trial;
  }
  // Tangents that point away from the other point: no biarc.
  EXPECT_FALSE(biarc(Vec2::Zero(), -Vec2::UnitX(), Vec2::UnitX(), -Vec2::UnitX()).has_value());
  EXPECT_FALSE(biarc(Vec2::Zero(), Vec2::UnitX(), Vec2::Zero(), Vec2::UnitX()).has_value());
}

TEST(Biarc, PointsOnACircleGiveThatCircleTwice) {
  const double r = 0.004;
  const Vec2 c(0.22, 0.01);
  const double a0 = 0.3, a1 = 0.42;
  const auto pieces = biarc(c + r * unit(a0), unit(a0 + std::numbers::pi / 2), c + r * unit(a1),
                            unit(a1 + std::numbers::pi / 2));
  ASSERT_TRUE(pieces.has_value());
  for (const PathSegment& piece : *pieces) {
    EXPECT_EQ(piece.kind, SegmentKind::arc);
    EXPECT_NEAR(curvature_1_m(piece), 1.0 / r, 1e-9 / r);
    EXPECT_NEAR((piece.center_m - c).norm(), 0.0, 1e-12);
  }
  // Collinear: one straight line in two pieces.
  const auto straight = biarc(Vec2::Zero(), Vec2::UnitX(), Vec2(1e-3, 0.0), Vec2::UnitX());
  ASSERT_TRUE(straight.has_value());
  EXPECT_EQ((*straight)[0].kind, SegmentKind::line);
  EXPECT_EQ((*straight)[1].kind, SegmentKind::line);
}

// An ellipse (semi-axes 30 and 12 mm) cut into chords of 0.25 mm, rounded to 0.1 µm like a CAM post.
std::vector<Vec2> ellipse_points(int n) {
  std::vector<Vec2> points;
  for (int k = 0; k <= n; ++k) {
    const double t = 2.0 * std::numbers::pi * k / n;
    const Vec2 p(0.222 + 0.030 * std::cos(t), 0.012 * std::sin(t));
    points.emplace_back(std::round(p.x() * 1e7) / 1e7, std::round(p.y() * 1e7) / 1e7);
  }
  return points;
}

// Signed curvature of the ellipse at the point nearest p (by its angle parameter, fine search).
double ellipse_curvature(const Vec2& p) {
  double best = INFINITY, kappa = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 20000;
    const Vec2 q(0.222 + 0.030 * std::cos(t), 0.012 * std::sin(t));
    if ((q - p).norm() < best) {
      best = (q - p).norm();
      kappa = 0.030 * 0.012 / std::pow(std::pow(0.030 * std::sin(t), 2) + std::pow(0.012 * std::cos(t), 2), 1.5);
    }
  }
  return kappa;
}

TEST(ChordFit, EllipseChordsBecomeOneTangentCurveWhoseCurvatureFollowsTheEllipse) {
  const std::vector<PathSegment> input = chords(ellipse_points(540), 10e-6);  // chords 0.25 … 0.35 mm
  const std::vector<PathSegment> output = fitted(input);
  expect_fits(input, output, 10e-6);
  // Every junction is tangent except none: the chain runs from the first chord's start to the last
  // chord's end as one curve (its ends are lines along the first and last chords).
  int arcs = 0;
  double worst_step = 0.0, worst_error = 0.0, max_curvature = 0.0;
  for (std::size_t k = 0; k < output.size(); ++k) {
    arcs += output[k].kind == SegmentKind::arc;
    if (k + 1 < output.size()) {
      ASSERT_LT(turn_angle_rad(end_tangent(output[k]), start_tangent(output[k + 1])), 1e-6) << "piece " << k;
      if (k >= 3 && k + 4 < output.size()) {  // the chain's ends step from its first and last chords' lines
        worst_step = std::max(worst_step, std::abs(curvature_1_m(output[k + 1]) - curvature_1_m(output[k])));
        }
    }
    if (output[k].kind == SegmentKind::arc && k >= 3 && k + 3 < output.size()) {
      const double truth = ellipse_curvature(point_at(output[k], 0.5 * output[k].length_m).position_m);
      worst_error = std::max(worst_error, std::abs(curvature_1_m(output[k]) - truth));
      max_curvature = std::max(max_curvature, truth);
    }
  }
  EXPECT_GT(arcs, 2 * 530);
  // The ellipse's curvature runs from 13.3 to 208 1/m. With a fillet at each vertex it would jump
  // between 0 and ~1/r at every chord; fitted, neighbouring pieces differ by a few % of the largest.
  EXPECT_NEAR(max_curvature, 208.3, 1.0);
  EXPECT_LT(worst_step, 0.05 * max_curvature);
  EXPECT_LT(worst_error, 0.05 * max_curvature);
}

TEST(ChordFit, ChordsTooCoarseForTheToleranceAreLeftForTheFillets) {
  // A 36-gon of radius 20 mm: chords of 3.5 mm whose sagitta (76 µm) is far beyond 2P = 20 µm.
  std::vector<Vec2> points;
  for (int k = 0; k <= 36; ++k) points.push_back(Vec2(0.222, 0.0) + 0.020 * unit(2.0 * std::numbers::pi * k / 36));
  const std::vector<PathSegment> input = chords(points, 10e-6);
  const std::vector<PathSegment> output = fitted(input);
  ASSERT_EQ(output.size(), input.size());
  for (std::size_t k = 0; k < input.size(); ++k) {
    EXPECT_EQ(output[k].kind, SegmentKind::line);
    EXPECT_EQ(output[k].start_m, input[k].start_m);
    EXPECT_EQ(output[k].end_m, input[k].end_m);
  }
  // The same polygon at P = 50 µm (2P = 100 µm ≥ 76 µm) is fitted.
  const std::vector<PathSegment> loose = fitted(chords(points, 50e-6));
  expect_fits(chords(points, 50e-6), loose, 50e-6);
  EXPECT_GT(loose.size(), 2 * input.size() - 4);
}

TEST(ChordFit, ACornerInsideAChainStaysACornerAndOnlyThereTheCurveStops) {
  // An arc of 0.2 mm chords (R = 10 mm) and a line of 0.2 mm chords meeting at a 40° corner: within
  // the 45° a chain may turn, but the circle through the corner and its neighbours (R = 0.3 mm) has a
  // sagitta of 16 µm on these chords, beyond 2P = 10 µm at P = 5 µm.
  std::vector<Vec2> points;
  for (int k = 0; k <= 100; ++k) points.push_back(Vec2(0.222, 0.0) + 0.010 * unit(-0.5 + 1.0 * k / 50.0));
  const Vec2 corner = points.back();
  const Vec2 heading = unit(-0.5 + 2.0 + std::numbers::pi / 2 + 0.7);  // 40° further round than the tangent
  for (int k = 1; k <= 50; ++k) points.push_back(corner + 0.0002 * k * heading);
  const std::vector<PathSegment> input = chords(points, 5e-6);
  const std::vector<PathSegment> output = fitted(input);
  expect_fits(input, output, 5e-6);
  int kinks = 0;
  for (std::size_t k = 0; k + 1 < output.size(); ++k) {
    const double turn = turn_angle_rad(end_tangent(output[k]), start_tangent(output[k + 1]));
    if (turn > 1e-6) {
      ++kinks;
      EXPECT_EQ(output[k].end_m, corner);
      EXPECT_NEAR(turn, 0.7, 0.05);
    }
  }
  EXPECT_EQ(kinks, 1);
}

TEST(ChordFit, LongChainsAreFittedInPiecesThatMeetTangentially) {
  // A 5 mm circle in 0.05 mm chords, seven turns: 4 403 chords, fitted in two pieces.
  std::vector<Vec2> many;
  const int per_turn = 629, n = 7 * per_turn;
  for (int k = 0; k <= n; ++k) many.push_back(Vec2(0.222, 0.0) + 0.005 * unit(2.0 * std::numbers::pi * k / per_turn));
  ASSERT_GT(many.size(), max_fitted_chain + 10);
  const std::vector<PathSegment> input = chords(many, 10e-6);
  const std::vector<PathSegment> output = fitted(input);
  ASSERT_FALSE(output.empty());
  for (std::size_t k = 0; k + 1 < output.size(); ++k) {
    ASSERT_EQ(output[k].end_m, output[k + 1].start_m);
    ASSERT_LT(turn_angle_rad(end_tangent(output[k]), start_tangent(output[k + 1])), 1e-6) << "piece " << k;
  }
  EXPECT_EQ(output.front().start_m, input.front().start_m);
  EXPECT_EQ(output.back().end_m, input.back().end_m);
}

TEST(ChordFit, OnlyG64LinesWithTheSameLaserStateAreChained) {
  std::vector<Vec2> points;
  for (int k = 0; k <= 40; ++k) points.push_back(Vec2(0.222, 0.0) + 0.010 * unit(0.01 * k));
  std::vector<PathSegment> input = chords(points, 10e-6);
  input[10].mode = JunctionMode::exact_stop;  // G61 at vertex 11
  input[25].laser_on = false;                 // the laser switches at vertices 25 and 26
  const std::vector<PathSegment> output = fitted(input);
  std::vector<Vec2> kinks;
  for (std::size_t k = 0; k + 1 < output.size(); ++k) {
    if (turn_angle_rad(end_tangent(output[k]), start_tangent(output[k + 1])) > 1e-6) kinks.push_back(output[k].end_m);
  }
  ASSERT_EQ(kinks.size(), 3u);
  EXPECT_EQ(kinks[0], points[11]);
  EXPECT_EQ(kinks[1], points[25]);
  EXPECT_EQ(kinks[2], points[26]);
}

}  // namespace
}  // namespace stiffpath::motion
