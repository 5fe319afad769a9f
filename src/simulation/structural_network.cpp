// The structural network's mechanics: arm springs, condensed arm stiffness and the compliance at the measured point.
#include "structural_network.hpp"

#include <algorithm>

namespace stiffpath::simulation::network {

namespace {

constexpr double kRigid = 1e-15;        // compliance floor: the element is rigid to far below 1 nm per kN
constexpr double kFreeRotation = 1e-9;  // N·m/rad on each body's ψ: keeps a body no bar holds determinate

// The inverse of a symmetric positive definite 3×3 by its cofactors (the twin evaluates C_true every step;
// a pivoting factorisation costs several times more). The physical floors keep the fitted networks' stiffnesses
// within ~10 decades of each other, well inside double precision.
Mat3 symmetric_inverse(const Mat3& m) {
  const double a = m(0, 0), b = m(0, 1), c = m(0, 2), d = m(1, 1), e = m(1, 2), f = m(2, 2);
  const double c00 = d * f - e * e, c01 = c * e - b * f, c02 = b * e - c * d;
  const double inv_det = 1.0 / (a * c00 + b * c01 + c * c02);
  Mat3 r;
  r(0, 0) = c00 * inv_det;
  r(0, 1) = r(1, 0) = c01 * inv_det;
  r(0, 2) = r(2, 0) = c02 * inv_det;
  r(1, 1) = (a * f - c * c) * inv_det;
  r(1, 2) = r(2, 1) = (b * c - a * e) * inv_det;
  r(2, 2) = (a * d - b * b) * inv_det;
  return r;
}

// The pin at B passes no moment, so the actuator and the proximal cantilever hold B by the inverse of their
// translational compliance at B: κ·(l_p n)(l_p n)ᵀ (a unit rotation about A moves B by l_p·n) + l_p/EA·e·eᵀ +
// l_p³/3EI·n·nᵀ, diagonal in (e, n).
detail::ArmSprings arm_springs(const ArmCompliance& a, double lp, double ld) {
  detail::ArmSprings s;
  s.along_e = 1.0 / (lp * std::max(a.proximal_axial_per_N, kRigid));
  s.across_e = 1.0 / (a.actuator_rad_per_Nm * lp * lp + lp * lp * lp / 3.0 * std::max(a.proximal_bending_per_Nm2, kRigid));
  s.proximal_bar = 1.0 / std::max(a.proximal_bar_m_per_N, kRigid);
  s.distal_link = 1.0 / std::max(ld * a.distal_axial_per_N, kRigid);
  s.distal_bar = 1.0 / std::max(a.distal_bar_m_per_N, kRigid);
  s.proximal_offset = a.proximal_bar_offset_m;
  s.distal_offset = a.distal_bar_offset_m;
  return s;
}

}  // namespace

std::array<detail::ArmSprings, 2> arm_springs(const std::array<ArmCompliance, 2>& arms, const kinematics::FiveBarGeometry& g) {
  return {arm_springs(arms[0], g.proximal_m[0], g.distal_m[0]), arm_springs(arms[1], g.proximal_m[1], g.distal_m[1])};
}

// Platform stiffness (x, y, ψ at C) of one arm: its elbow body (B, ψ_E) condensed out.
Mat3 arm_stiffness(const ArmPose& g, const detail::ArmSprings& a) {
  const Vec2 n(-g.e.y(), g.e.x());
  Mat3 kaa = Mat3::Zero();  // elbow body (B, ψ_E)
  kaa.topLeftCorner<2, 2>() = a.along_e * g.e * g.e.transpose() + a.across_e * n * n.transpose();
  kaa(2, 2) = kFreeRotation;
  // Proximal parallelogram bar: base pivot A + d → body pivot B + d, along e.
  const Vec3 gp(g.e.x(), g.e.y(), cross(a.proximal_offset, g.e));
  kaa.noalias() += a.proximal_bar * gp * gp.transpose();
  // Both the distal link and the distal bar join the elbow body to the platform along u, with h = (u, d × u) on
  // the platform's side and −h on the body's: each adds k·h·hᵀ to the platform's block and to the body's, and
  // −k·h·hᵀ to the coupling, so one symmetric B = Σ k·h·hᵀ carries all three.
  const Vec3 hl(g.u.x(), g.u.y(), 0.0), hb(g.u.x(), g.u.y(), cross(a.distal_offset, g.u));
  Mat3 bars = a.distal_link * hl * hl.transpose();
  bars.noalias() += a.distal_bar * hb * hb.transpose();
  kaa += bars;
  Mat3 kpp = bars;
  kpp(2, 2) += kFreeRotation;
  return kpp - bars * symmetric_inverse(kaa) * bars;
}

// The compliance at the measured point from the arms' platform stiffness k (their sum) and the base.
Mat2 network_compliance(const Mat3& k, const BaseCompliance& base, const Vec2& offset, const Vec2& p, const Vec2& a0) {
  // Force at G = C + offset: the wrench at C is (F, offset × F); G moves by δC + ψ·k × offset. So
  // C_G = Gᵀ·K⁻¹·G with G's columns (1, 0, −offset_y) and (0, 1, offset_x).
  const Mat3 kc = symmetric_inverse(k);
  const Vec3 gx(1.0, 0.0, -offset.y()), gy(0.0, 1.0, offset.x());
  const Vec3 kx = kc * gx, ky = kc * gy;
  const double cxy = 0.5 * (gx.dot(ky) + gy.dot(kx));
  Mat2 c;
  c << gx.dot(kx), cxy, cxy, gy.dot(ky);
  // The base frame under both arms, in series with them: translation, and rotation about the actuators'
  // midpoint A_0, which moves p by ψ·k × (p − A_0).
  const Vec2 w(a0.y() - p.y(), p.x() - a0.x());
  c(0, 0) += base.x_m_per_N;
  c(1, 1) += base.y_m_per_N;
  return c + base.rotation_rad_per_Nm * w * w.transpose();
}

Mat2 network_compliance(const Pose& pose, const std::array<detail::ArmSprings, 2>& arms, const BaseCompliance& base,
                        const Vec2& offset, const Vec2& p, const Vec2& a0) {
  return network_compliance(arm_stiffness(pose[0], arms[0]) + arm_stiffness(pose[1], arms[1]), base, offset, p, a0);
}

// The arms' poses at p (p within reach).
Pose pose_at(const kinematics::FiveBar& five_bar, const kinematics::Vec2& q, const Vec2& p) {
  const auto& g = five_bar.geometry();
  const auto elbow = five_bar.elbows(q);
  Pose pose;
  for (std::size_t i = 0; i < 2; ++i) {
    pose[i].A = g.actuator_m[i];
    pose[i].B = elbow[i];
    pose[i].lp = g.proximal_m[i];
    pose[i].ld = g.distal_m[i];
    pose[i].e = (pose[i].B - pose[i].A) / pose[i].lp;
    pose[i].u = (p - pose[i].B) / pose[i].ld;
  }
  return pose;
}

Vec2 midpoint(const kinematics::FiveBar& five_bar) {
  return 0.5 * (five_bar.geometry().actuator_m[0] + five_bar.geometry().actuator_m[1]);
}

}  // namespace stiffpath::simulation::network
