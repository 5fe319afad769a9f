// Property tests of the general five-bar over random geometries and all four working modes, against an independent circle-intersection solver.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>

#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/five_bar.hpp"

namespace stiffpath::kinematics {
namespace {

constexpr unsigned kSeed = 20261122;
constexpr double kPi = std::numbers::pi;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
double wrap(double a) { return std::remainder(a, 2 * kPi); }

// The two intersections of the circles (c1, r1) and (c2, r2), by the angle at c1 (law of cosines).
std::optional<std::array<Vec2, 2>> intersections(const Vec2& c1, double r1, const Vec2& c2, double r2) {
  const Vec2 d = c2 - c1;
  const double D = d.norm();
  const double cos_a = (D * D + r1 * r1 - r2 * r2) / (2 * D * r1);
  if (!(D > 0) || std::abs(cos_a) > 1) return std::nullopt;
  const double base = std::atan2(d.y(), d.x()), a = std::acos(cos_a);
  return std::array<Vec2, 2>{c1 + r1 * Vec2(std::cos(base + a), std::sin(base + a)),
                             c1 + r1 * Vec2(std::cos(base - a), std::sin(base - a))};
}

// A random five-bar: actuators 0–120 mm apart anywhere near the origin, links 60–200 mm.
FiveBarGeometry random_geometry(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> pos(-0.06, 0.06), len(0.06, 0.20);
  FiveBarGeometry g;
  g.actuator_m = {Vec2(pos(rng), pos(rng) * 0.3), Vec2(pos(rng), pos(rng) * 0.3)};
  g.proximal_m = {len(rng), len(rng)};
  g.distal_m = {len(rng), len(rng)};
  return g;
}

// A configuration reached from random joint angles: the end point, its working and assembly modes.
struct Pose {
  Vec2 q, c;
  std::array<Vec2, 2> b;
  std::array<int, 2> elbows;
  int assembly;
};
std::optional<Pose> random_pose(const FiveBarGeometry& g, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::uniform_int_distribution<int> pick(0, 1);
  Pose p;
  p.q = {angle(rng), angle(rng)};
  for (int i = 0; i < 2; ++i) p.b[i] = g.actuator_m[i] + g.proximal_m[i] * Vec2(std::cos(p.q[i]), std::sin(p.q[i]));
  const auto c = intersections(p.b[0], g.distal_m[0], p.b[1], g.distal_m[1]);
  if (!c) return std::nullopt;
  p.c = (*c)[pick(rng)];
  for (int i = 0; i < 2; ++i) p.elbows[i] = cross(p.c - g.actuator_m[i], p.b[i] - g.actuator_m[i]) > 0 ? 1 : -1;
  p.assembly = cross(p.c - p.b[0], p.c - p.b[1]) > 0 ? 1 : -1;
  return p;
}

const SingularityMargin kLoose{1e-4, 1e4, 0.02};  // 0.1 mm, κ ≤ 10⁴, 1.1° from collinear

TEST(GeneralFiveBar, InverseRecoversTheJointsAndForwardTheEndPointInAllFourModes) {
  std::mt19937_64 rng(kSeed);
  std::array<int, 4> per_mode{};
  double worst_q = 0, worst_p = 0;
  for (int trial = 0; trial < 40000; ++trial) {
    FiveBarGeometry g = random_geometry(rng);
    const auto pose = random_pose(g, rng);
    if (!pose) continue;
    g.elbows = pose->elbows;
    g.assembly = pose->assembly;
    const FiveBar robot(g, kLoose);
    InverseFrame frame;
    const InverseResult r = robot.solve_inverse(pose->c, frame);
    if (r.status != Reach::ok) continue;
    ++per_mode[static_cast<std::size_t>((g.elbows[0] > 0 ? 0 : 2) + (g.elbows[1] > 0 ? 0 : 1))];
    worst_q = std::max({worst_q, std::abs(wrap(r.q.x() - pose->q.x())), std::abs(wrap(r.q.y() - pose->q.y()))});
    worst_p = std::max(worst_p, (robot.forward(r.q) - pose->c).norm());
    ASSERT_GE(r.q.x(), -kPi);  // the default window [−π, π)
    ASSERT_LT(r.q.y(), kPi);
    // The passive angles are the distal links' directions.
    const auto passive = robot.passive_angles(r.q);
    ASSERT_NEAR(wrap(passive.theta3_rad - std::atan2(pose->c.y() - pose->b[0].y(), pose->c.x() - pose->b[0].x())), 0, 1e-8);
    ASSERT_NEAR(wrap(passive.theta4_rad - std::atan2(pose->c.y() - pose->b[1].y(), pose->c.x() - pose->b[1].x())), 0, 1e-8);
    ASSERT_LT((frame.jacobian - robot.jacobian(r.q)).norm(), 1e-9 * (1 + frame.jacobian.norm()));
  }
  for (int mode = 0; mode < 4; ++mode) EXPECT_GT(per_mode[static_cast<std::size_t>(mode)], 1000) << "mode " << mode;
  // Near-singular poses (κ up to 10⁴) amplify rounding; well inside, the match is to 1e-12.
  EXPECT_LT(worst_q, 1e-7);
  EXPECT_LT(worst_p, 1e-10);
}

TEST(GeneralFiveBar, JacobianAndItsDerivativeMatchFiniteDifferences) {
  std::mt19937_64 rng(kSeed + 1);
  std::uniform_real_distribution<double> rate(-10.0, 10.0);
  const SingularityMargin margin{2e-3, 20.0, 0.2};  // away from singularities, so differences are accurate
  int tested = 0;
  for (int trial = 0; trial < 20000 && tested < 3000; ++trial) {
    FiveBarGeometry g = random_geometry(rng);
    const auto pose = random_pose(g, rng);
    if (!pose) continue;
    g.elbows = pose->elbows;
    g.assembly = pose->assembly;
    const FiveBar robot(g, margin);
    InverseFrame frame;
    const InverseResult r = robot.solve_inverse(pose->c, frame);
    if (r.status != Reach::ok) continue;
    ++tested;
    const double h = 1e-6;
    Mat2 J_numeric;
    for (int k = 0; k < 2; ++k) {
      Vec2 dq = Vec2::Zero();
      dq[k] = h;
      J_numeric.col(k) = (robot.forward(r.q + dq) - robot.forward(r.q - dq)) / (2 * h);
    }
    ASSERT_LT((frame.jacobian - J_numeric).norm(), 1e-7 * (1 + J_numeric.norm())) << trial;
    const Vec2 qd{rate(rng), rate(rng)};
    const Mat2 Jd_numeric = (robot.jacobian(r.q + qd * h) - robot.jacobian(r.q - qd * h)) / (2 * h);
    ASSERT_LT((robot.jacobian_dot(frame, qd) - Jd_numeric).norm(), 1e-6 * (1 + Jd_numeric.norm())) << trial;
    ASSERT_LT((robot.jacobian_dot(r.q, qd) - robot.jacobian_dot(frame, qd)).norm(), 1e-9 * (1 + Jd_numeric.norm()));
    // Velocity and acceleration levels: p̈ of q(t) = q + q̇t + q̈t²/2 by second differences of FK.
    const Vec2 qdd{rate(rng) * 100, rate(rng) * 100};
    const double t = 1e-5;  // small: near a singularity the fourth derivative of FK is large
    const auto p_at = [&](double s) { return robot.forward(r.q + qd * s + 0.5 * qdd * s * s); };
    const Vec2 pdd_numeric = (p_at(t) - 2 * p_at(0) + p_at(-t)) / (t * t);
    ASSERT_LT((robot.acceleration(r.q, qd, qdd) - pdd_numeric).norm(), 1e-4 * (1 + pdd_numeric.norm()));
    ASSERT_LT((robot.joint_acceleration(r.q, qd, robot.acceleration(r.q, qd, qdd)) - qdd).norm(), 1e-8 * (1 + qdd.norm()));
    ASSERT_LT((robot.joint_velocity(r.q, robot.velocity(r.q, qd)) - qd).norm(), 1e-9 * (1 + qd.norm()));
  }
  EXPECT_EQ(tested, 3000);
}

// The reach verdict of a point by hand: every margin computed independently, in the documented order.
Reach expected_reach(const FiveBar& robot, const Vec2& p) {
  const auto& g = robot.geometry();
  const auto& m = robot.margin();
  for (int i = 0; i < 2; ++i) {
    if ((p - g.actuator_m[i]).norm() > g.proximal_m[i] + g.distal_m[i] - m.min_distance_m) return Reach::near_stretched;
  }
  for (int i = 0; i < 2; ++i) {
    if ((p - g.actuator_m[i]).norm() < std::abs(g.proximal_m[i] - g.distal_m[i]) + m.min_distance_m) {
      return Reach::near_origin;
    }
  }
  std::array<Vec2, 2> b;
  for (int i = 0; i < 2; ++i) {
    const auto cand = intersections(g.actuator_m[i], g.proximal_m[i], p, g.distal_m[i]);
    if (!cand) return Reach::near_stretched;  // cannot happen after the distance checks
    const int s0 = cross(p - g.actuator_m[i], (*cand)[0] - g.actuator_m[i]) > 0 ? 1 : -1;
    b[i] = s0 == g.elbows[i] ? (*cand)[0] : (*cand)[1];
  }
  const Vec2 u1 = (p - b[0]).normalized(), u2 = (p - b[1]).normalized();
  const double sine = g.assembly * cross(u1, u2);
  if (sine < -std::sin(m.min_distal_angle_rad)) return Reach::other_assembly;
  if (sine < std::sin(m.min_distal_angle_rad)) return Reach::near_parallel;
  const double theta1 = std::atan2(b[0].y() - g.actuator_m[0].y(), b[0].x() - g.actuator_m[0].x());
  const double theta2 = std::atan2(b[1].y() - g.actuator_m[1].y(), b[1].x() - g.actuator_m[1].x());
  const double kappa = robot.condition_number({theta1, theta2});
  return kappa <= m.max_condition_number ? Reach::ok : Reach::ill_conditioned;
}

TEST(GeneralFiveBar, ReachMarginsAreTheDocumentedOnesOverThePlane) {
  std::mt19937_64 rng(kSeed + 2);
  std::uniform_real_distribution<double> u(-0.45, 0.45);
  std::uniform_int_distribution<int> sign(0, 1);
  std::array<int, 7> seen{};
  int mismatches = 0;
  for (int geometry = 0; geometry < 60; ++geometry) {
    FiveBarGeometry g = random_geometry(rng);
    g.elbows = {sign(rng) ? 1 : -1, sign(rng) ? 1 : -1};
    g.assembly = sign(rng) ? 1 : -1;
    const FiveBar robot(g, {0.004, 6.0, 0.25});
    for (int k = 0; k < 3000; ++k) {
      const Vec2 p{u(rng), u(rng)};
      const Reach got = robot.solve_inverse(p).status;
      ++seen[static_cast<std::size_t>(got)];
      // Exactly at a threshold the two computations may round differently: allow a handful.
      if (got != expected_reach(robot, p)) ++mismatches;
      const InverseResult r = robot.solve_inverse(p);
      ASSERT_TRUE(r.q.allFinite());
      ASSERT_EQ(robot.check_reach(p), got);
      if (got != Reach::ok) {
        ASSERT_EQ(r.q, Vec2::Zero());
        ASSERT_FALSE(robot.explain(p).empty());
      }
    }
  }
  EXPECT_LE(mismatches, 2);
  for (const Reach r : {Reach::ok, Reach::near_stretched, Reach::near_origin, Reach::near_parallel, Reach::other_assembly,
                        Reach::ill_conditioned}) {
    EXPECT_GT(seen[static_cast<std::size_t>(r)], 50) << describe(r);
  }
}

TEST(GeneralFiveBar, AssemblyModeChoosesTheIntersectionAndTheOtherIsRefused) {
  // A symmetric robot with actuators 80 mm apart: the mirror image of C across B1B2 is the other assembly.
  FiveBarGeometry g;
  g.actuator_m = {Vec2(-0.04, 0.0), Vec2(0.04, 0.0)};
  g.proximal_m = {0.12, 0.12};
  g.distal_m = {0.18, 0.18};
  const FiveBar up(g, {});
  const Vec2 p{0.01, 0.22};
  const Vec2 q = up.inverse(p);
  EXPECT_LT((up.forward(q) - p).norm(), 1e-13);
  FiveBarGeometry other = g;
  other.assembly = -1;
  const FiveBar down(other, {});
  const Vec2 mirrored = down.forward(q);
  const auto b = up.elbows(q);
  // Same distances to both elbows, on the other side of the line B1B2.
  EXPECT_NEAR((mirrored - b[0]).norm(), 0.18, 1e-13);
  EXPECT_NEAR((mirrored - b[1]).norm(), 0.18, 1e-13);
  EXPECT_LT(cross(b[1] - b[0], p - b[0]) * cross(b[1] - b[0], mirrored - b[0]), 0.0);
  EXPECT_EQ(down.check_reach(p), Reach::other_assembly);
  EXPECT_NE(down.explain(p).find("other assembly mode"), std::string::npos);
}

TEST(GeneralFiveBar, ForwardCheckedRefusesALoopThatCannotClose) {
  FiveBarGeometry g;
  g.actuator_m = {Vec2(-0.04, 0.0), Vec2(0.04, 0.0)};
  g.proximal_m = {0.12, 0.13};
  g.distal_m = {0.05, 0.05};
  const FiveBar robot(g, {0.001, 8.0});
  const Vec2 apart{kPi, 0.0};  // elbows 330 mm apart, distal links 100 mm together
  EXPECT_THROW((void)robot.forward_checked(apart), Error);
  EXPECT_TRUE(robot.forward(apart).allFinite());
}

TEST(GeneralFiveBar, AnglesComeOutInTheJointWindow) {
  // The left arm of a robot reaching up-left turns past 180°: with the window starting at 0 the
  // angle is reported in [0, 2π), not as a negative angle.
  FiveBarGeometry g;
  g.actuator_m = {Vec2(-0.04, 0.0), Vec2(0.04, 0.0)};
  g.proximal_m = {0.12, 0.13};
  g.distal_m = {0.18, 0.17};
  const Vec2 p{-0.20, 0.02};
  const FiveBar plain(g, {});
  const FiveBar windowed(g, {}, {0.0, -0.5});
  const InverseResult a = plain.solve_inverse(p), b = windowed.solve_inverse(p);
  ASSERT_EQ(a.status, Reach::ok);
  EXPECT_NEAR(wrap(a.q.x() - b.q.x()), 0.0, 1e-15);
  EXPECT_GE(b.q.x(), 0.0);
  EXPECT_LT(b.q.x(), 2 * kPi);
  EXPECT_GE(b.q.y(), -0.5);
  EXPECT_LT(a.q.x(), 0.0);  // the default window [−π, π) gives the negative twin
}

TEST(GeneralFiveBar, GeneralFormulasAgreeWithTheThesisClosedForms) {
  // The thesis robot with its left actuator moved by 1e-300 m takes the general path; it must agree
  // with eqs. 2.1–2.2 to rounding, refuse the same points and give the same J and J̇.
  FiveBarGeometry g = FiveBarGeometry::thesis(0.150);
  const FiveBar thesis(g, {});
  g.actuator_m[0].x() = 1e-300;
  const FiveBar general(g, {});
  ASSERT_TRUE(thesis.thesis_case());
  ASSERT_FALSE(general.thesis_case());
  std::mt19937_64 rng(kSeed + 3);
  std::uniform_real_distribution<double> u(-0.31, 0.31), rate(-20, 20);
  int ok = 0, differ = 0;
  for (int k = 0; k < 50000; ++k) {
    const Vec2 p{u(rng), u(rng)};
    InverseFrame ft, fg;
    const InverseResult a = thesis.solve_inverse(p, ft), b = general.solve_inverse(p, fg);
    if (a.status != b.status) {
      ++differ;  // only at a threshold's rounding
      continue;
    }
    if (a.status != Reach::ok) continue;
    ++ok;
    ASSERT_LT(std::abs(wrap(a.q.x() - b.q.x())) + std::abs(wrap(a.q.y() - b.q.y())), 1e-12);
    ASSERT_LT((ft.jacobian - fg.jacobian).norm(), 1e-12);
    ASSERT_NEAR(a.condition_number, b.condition_number, 1e-9 * a.condition_number);
    const Vec2 qd{rate(rng), rate(rng)};
    ASSERT_LT((thesis.jacobian_dot(ft, qd) - general.jacobian_dot(fg, qd)).norm(), 1e-10);
    ASSERT_LT((thesis.forward(a.q) - general.forward(a.q)).norm(), 1e-15);
  }
  EXPECT_GT(ok, 20000);
  EXPECT_LE(differ, 3);
}

TEST(GeneralFiveBar, JointZeroOffsetsShiftTheJointReadingsAndNothingElse) {
  // A robot whose links stand δ_i ahead of its joint readings: forward(q) is the offset-free robot's at q + δ,
  // inverse(p) its angles minus δ, and J, κ, the elbows and the reach are the same at corresponding angles.
  std::mt19937_64 rng(kSeed + 9);
  std::uniform_real_distribution<double> u(-0.35, 0.35), off(-0.05, 0.05);
  int checked = 0;
  for (int g_k = 0; g_k < 20; ++g_k) {
    FiveBarGeometry plain = random_geometry(rng);
    FiveBarGeometry shifted = plain;
    shifted.joint_zero_rad = {off(rng), off(rng)};
    const Vec2 delta(shifted.joint_zero_rad[0], shifted.joint_zero_rad[1]);
    ASSERT_FALSE(shifted == plain);
    const FiveBar a(plain, kLoose), b(shifted, kLoose);
    for (int k = 0; k < 200; ++k) {
      const Vec2 p{u(rng), u(rng)};
      const InverseResult ra = a.solve_inverse(p), rb = b.solve_inverse(p);
      ASSERT_EQ(ra.status, rb.status);
      if (ra.status != Reach::ok) continue;
      ++checked;
      EXPECT_NEAR(wrap(rb.q.x() - (ra.q.x() - delta.x())), 0.0, 1e-12);
      EXPECT_NEAR(wrap(rb.q.y() - (ra.q.y() - delta.y())), 0.0, 1e-12);
      EXPECT_LT((b.forward(rb.q) - p).norm(), 1e-12);
      EXPECT_LT((b.forward(rb.q) - a.forward(ra.q)).norm(), 1e-12);
      EXPECT_LT((b.jacobian(rb.q) - a.jacobian(ra.q)).norm(), 1e-9);
      EXPECT_NEAR(b.condition_number(rb.q), a.condition_number(ra.q), 1e-9 * a.condition_number(ra.q));
      EXPECT_LT((b.elbows(rb.q)[0] - a.elbows(ra.q)[0]).norm(), 1e-12);
      const Vec2 qd{0.3, -0.7};
      EXPECT_LT((b.jacobian_dot(rb.q, qd) - a.jacobian_dot(ra.q, qd)).norm(), 1e-9);
      EXPECT_NEAR(wrap(b.passive_angles(rb.q).theta3_rad - a.passive_angles(ra.q).theta3_rad), 0.0, 1e-12);
    }
  }
  EXPECT_GT(checked, 200);
  // The thesis's robot with an offset leaves its closed forms, and the general path gives eq. 2.1 at q + δ.
  FiveBarGeometry thesis = FiveBarGeometry::thesis(0.150);
  thesis.joint_zero_rad = {1e-3, -2e-3};
  EXPECT_FALSE(thesis.is_thesis_case());
  const FiveBar t(thesis, {});
  const Vec2 q(0.9, -0.4), l(0.9 + 1e-3, -0.4 - 2e-3);
  EXPECT_LT((t.forward(q) - 0.150 * Vec2(std::cos(l.x()) + std::cos(l.y()), std::sin(l.x()) + std::sin(l.y()))).norm(), 1e-15);
}

}  // namespace
}  // namespace stiffpath::kinematics
