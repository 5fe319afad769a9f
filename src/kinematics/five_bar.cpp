// The five-bar's construction, the thesis's closed forms (eqs. 2.1–2.2) and the general inverse kinematics.
#include "stiffpath/kinematics/five_bar.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>

#include "stiffpath/core/error.hpp"

namespace stiffpath::kinematics {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();

bool finite_positive(double v) noexcept { return std::isfinite(v) && v > 0.0; }

// 2-norm condition number of a 2×2 matrix from its Frobenius norm and determinant.
double condition_of(const Mat2& J) noexcept {
  const double s = J.squaredNorm(), d = std::abs(J(0, 0) * J(1, 1) - J(0, 1) * J(1, 0));
  if (!(d > 0.0) || !std::isfinite(s)) return kInfinity;
  return (s + std::sqrt(std::max(s * s - 4.0 * d * d, 0.0))) / (2.0 * d);
}

double cross(const Vec2& a, const Vec2& b) noexcept { return a.x() * b.y() - a.y() * b.x(); }
}  // namespace

FiveBarGeometry FiveBarGeometry::thesis(double link_length_m) noexcept {
  FiveBarGeometry g;
  g.proximal_m = {link_length_m, link_length_m};
  g.distal_m = {link_length_m, link_length_m};
  return g;
}

bool FiveBarGeometry::is_thesis_case() const noexcept {
  const double l = proximal_m[0];
  return actuator_m[0].x() == 0.0 && actuator_m[0].y() == 0.0 && actuator_m[1].x() == 0.0 &&
         actuator_m[1].y() == 0.0 && proximal_m[1] == l && distal_m[0] == l && distal_m[1] == l && elbows[0] == 1 &&
         elbows[1] == -1 && assembly == 1 && joint_zero_rad[0] == 0.0 && joint_zero_rad[1] == 0.0;
}

bool FiveBarGeometry::operator==(const FiveBarGeometry& o) const noexcept {
  return actuator_m == o.actuator_m && proximal_m == o.proximal_m && distal_m == o.distal_m && elbows == o.elbows &&
         assembly == o.assembly && joint_zero_rad == o.joint_zero_rad;
}

bool FiveBarGeometry::mirror_symmetric_about_x() const noexcept {
  return actuator_m[0].x() == actuator_m[1].x() && actuator_m[0].y() == -actuator_m[1].y() &&
         proximal_m[0] == proximal_m[1] && distal_m[0] == distal_m[1] && elbows[0] == -elbows[1];
}

FiveBar::FiveBar(double link_length_m, SingularityMargin margin)
    : FiveBar(FiveBarGeometry::thesis(link_length_m), margin) {}

FiveBar::FiveBar(const FiveBarGeometry& geometry, SingularityMargin margin, std::array<double, 2> angle_floor_rad)
    : g_(geometry), margin_(margin), angle_floor_(angle_floor_rad) {
  for (int i = 0; i < 2; ++i) {
    const char* side = i == 0 ? "left" : "right";
    if (!finite_positive(g_.proximal_m[i]) || !finite_positive(g_.distal_m[i])) {
      throw Error(fmt::format("five-bar: the {} arm's link lengths must be positive and finite", side));
    }
    if (!g_.actuator_m[i].allFinite()) throw Error(fmt::format("five-bar: the {} actuator's position is not finite", side));
    if (g_.elbows[i] != 1 && g_.elbows[i] != -1) throw Error(fmt::format("five-bar: the {} elbow must be +1 or -1", side));
    if (!std::isfinite(angle_floor_[i])) throw Error("five-bar: joint angle window must be finite");
    if (!std::isfinite(g_.joint_zero_rad[i])) throw Error(fmt::format("five-bar: the {} joint's zero offset is not finite", side));
  }
  if (g_.assembly != 1 && g_.assembly != -1) throw Error("five-bar: assembly mode must be +1 or -1");
  const double shortest = std::min({g_.proximal_m[0], g_.proximal_m[1], g_.distal_m[0], g_.distal_m[1]});
  if (!(margin_.min_distance_m >= 0.0 && margin_.min_distance_m < shortest)) {
    throw Error(fmt::format("singularity margin min_distance must lie in [0, {:.3f} mm) (the shortest link)",
                            shortest * 1e3));
  }
  if (!(margin_.max_condition_number > 1.0)) throw Error("singularity margin max_condition_number must exceed 1");
  if (!(margin_.min_distal_angle_rad >= 0.0 && margin_.min_distal_angle_rad < std::numbers::pi / 2)) {
    throw Error("singularity margin min_distal_angle must lie in [0, 90) deg");
  }
  thesis_ = g_.is_thesis_case();
  l_ = g_.proximal_m[0];
  inverse_2l_ = 1.0 / (2.0 * l_);
  for (int i = 0; i < 2; ++i) {
    arm_[i].outer_m = g_.proximal_m[i] + g_.distal_m[i] - margin_.min_distance_m;
    arm_[i].inner_m = std::abs(g_.proximal_m[i] - g_.distal_m[i]) + margin_.min_distance_m;
  }
  min_distal_sine_ = std::sin(margin_.min_distal_angle_rad);
}

Vec2 FiveBar::forward(const Vec2& q) const noexcept {
  if (thesis_) return {l_ * (std::cos(q.x()) + std::cos(q.y())), l_ * (std::sin(q.x()) + std::sin(q.y()))};
  Vec2 c;
  std::array<Vec2, 2> u;
  close_loop(q, c, u);
  return c;
}

Vec2 FiveBar::forward_checked(const Vec2& q) const {
  Vec2 c;
  std::array<Vec2, 2> u;
  if (!thesis_ && !close_loop(q, c, u)) {
    throw Error(fmt::format("joint angles (theta1 = {:.4f} deg, theta2 = {:.4f} deg): the distal links cannot meet "
                            "(the elbows are {:.4f} mm apart, the distal links {:.4f} and {:.4f} mm long)",
                            q.x() * 180 / std::numbers::pi, q.y() * 180 / std::numbers::pi,
                            (elbows(q)[1] - elbows(q)[0]).norm() * 1e3, g_.distal_m[0] * 1e3, g_.distal_m[1] * 1e3));
  }
  return forward(q);
}

std::array<Vec2, 2> FiveBar::elbows(const Vec2& q_joint) const noexcept {
  const Vec2 q = links(q_joint);
  return {g_.actuator_m[0] + g_.proximal_m[0] * Vec2(std::cos(q.x()), std::sin(q.x())),
          g_.actuator_m[1] + g_.proximal_m[1] * Vec2(std::cos(q.y()), std::sin(q.y()))};
}

// q: joint readings; the link angles are q + δ.
bool FiveBar::close_loop(const Vec2& q_joint, Vec2& c, std::array<Vec2, 2>& u) const noexcept {
  const auto b = elbows(q_joint);
  const Vec2 q = links(q_joint);
  const Vec2 d = b[1] - b[0];
  const double dist = d.norm(), l1 = g_.distal_m[0], l2 = g_.distal_m[1];
  if (!(dist > 0.0)) {
    c = b[0] + l1 * Vec2(std::cos(q.x()), std::sin(q.x()));
    u = {(c - b[0]) / l1, (c - b[1]) / l2};
    return false;
  }
  // C = M ± h·d⊥/|d|: M on B1B2 at a from B1, h the half chord of the two circles.
  const double a = (l1 * l1 - l2 * l2 + dist * dist) / (2.0 * dist);
  const double h2 = l1 * l1 - a * a;
  const double h = std::sqrt(std::max(h2, 0.0));
  const Vec2 along = d / dist, across(-along.y(), along.x());
  c = b[0] + a * along + static_cast<double>(g_.assembly) * h * across;
  u = {(c - b[0]) / l1, (c - b[1]) / l2};
  return h2 >= 0.0;
}

Reach FiveBar::check_reach(const Vec2& p) const noexcept { return solve_inverse(p).status; }

InverseResult FiveBar::solve_inverse(const Vec2& p) const noexcept {
  return thesis_ ? solve_thesis(p, nullptr) : solve_general(p, nullptr);
}

InverseResult FiveBar::solve_inverse(const Vec2& p, InverseFrame& frame) const noexcept {
  return thesis_ ? solve_thesis(p, &frame) : solve_general(p, &frame);
}

InverseResult FiveBar::solve_inverse(const Vec2& p, Mat2& jacobian) const noexcept {
  InverseFrame frame;
  const InverseResult r = solve_inverse(p, frame);
  if (r.status == Reach::ok) jacobian = frame.jacobian;
  return r;
}

InverseResult FiveBar::solve_thesis(const Vec2& p, InverseFrame* frame) const noexcept {
  // The reach check written out so that r, cos η and sin η are computed once, and with two divisions:
  // this is the real-time path.
  InverseResult result;
  result.condition_number = kInfinity;
  if (!std::isfinite(p.x()) || !std::isfinite(p.y())) {
    result.status = Reach::not_finite;
    return result;
  }
  const double r = p.norm();
  if (r > 2.0 * l_ - margin_.min_distance_m) {
    result.status = Reach::near_stretched;
    return result;
  }
  if (r < margin_.min_distance_m) {
    result.status = Reach::near_origin;
    return result;
  }
  const double c_eta = r * inverse_2l_;
  const double s_eta = c_eta >= 1.0 ? 0.0 : std::sqrt(1.0 - c_eta * c_eta);
  // The distal links meet at the angle θ1 − θ2 = 2η: |u1 × u2| = sin 2η.
  if (!(2.0 * s_eta * c_eta >= min_distal_sine_)) {
    result.status = Reach::near_parallel;
    return result;
  }
  // κ = max(tan η, cot η) = max(c, s) / min(c, s), with one division.
  const double condition = c_eta >= 1.0 || c_eta <= 0.0 || s_eta <= 0.0 ? kInfinity
                                                                         : std::max(c_eta, s_eta) / std::min(c_eta, s_eta);
  if (!(condition <= margin_.max_condition_number)) {
    result.status = Reach::ill_conditioned;
    return result;
  }
  result.status = Reach::ok;
  const double phi = std::atan2(p.y(), p.x());
  const double eta = std::acos(c_eta);
  result.q = {phi + eta, phi - eta};
  result.condition_number = condition;
  if (frame) {
    const double inverse_r = 1.0 / r;
    const double c_phi = p.x() * inverse_r, s_phi = p.y() * inverse_r;
    // cos/sin of φ ± η by the angle-sum identities.
    const double c1 = c_phi * c_eta - s_phi * s_eta, s1 = s_phi * c_eta + c_phi * s_eta;
    const double c2 = c_phi * c_eta + s_phi * s_eta, s2 = s_phi * c_eta - c_phi * s_eta;
    frame->jacobian << -l_ * s1, -l_ * s2, l_ * c1, l_ * c2;
    frame->proximal = {Vec2(c1, s1), Vec2(c2, s2)};
    frame->distal = {Vec2(c2, s2), Vec2(c1, s1)};  // AC ∥ A0B, BC ∥ A0A
  }
  return result;
}

InverseResult FiveBar::solve_general(const Vec2& p, InverseFrame* frame) const noexcept {
  InverseResult result;
  result.condition_number = kInfinity;
  if (!std::isfinite(p.x()) || !std::isfinite(p.y())) {
    result.status = Reach::not_finite;
    return result;
  }
  std::array<Vec2, 2> d;
  std::array<double, 2> r{};
  for (int i = 0; i < 2; ++i) {
    d[i] = p - g_.actuator_m[i];
    r[i] = d[i].norm();
    if (r[i] > arm_[i].outer_m) {
      result.status = Reach::near_stretched;
      return result;
    }
  }
  for (int i = 0; i < 2; ++i) {
    if (!(r[i] >= arm_[i].inner_m) || !(r[i] > 0.0)) {
      result.status = Reach::near_origin;
      return result;
    }
  }
  std::array<Vec2, 2> e, u;
  for (int i = 0; i < 2; ++i) {
    const double lp = g_.proximal_m[i], ld = g_.distal_m[i], s = g_.elbows[i];
    const double c_alpha = std::clamp((r[i] * r[i] + lp * lp - ld * ld) / (2.0 * r[i] * lp), -1.0, 1.0);
    const double s_alpha = std::sqrt(1.0 - c_alpha * c_alpha);
    const double inverse_r = 1.0 / r[i];
    const double c_phi = d[i].x() * inverse_r, s_phi = d[i].y() * inverse_r;
    e[i] = {c_phi * c_alpha - s * s_phi * s_alpha, s_phi * c_alpha + s * c_phi * s_alpha};
    u[i] = (d[i] - lp * e[i]) / ld;
    double theta = std::atan2(d[i].y(), d[i].x()) + s * std::acos(c_alpha) - g_.joint_zero_rad[i];
    theta -= 2.0 * std::numbers::pi * std::floor((theta - angle_floor_[i]) / (2.0 * std::numbers::pi));
    result.q[i] = theta;
  }
  const double sine = static_cast<double>(g_.assembly) * cross(u[0], u[1]);
  if (sine < -min_distal_sine_) {
    result.q.setZero();
    result.status = Reach::other_assembly;
    return result;
  }
  if (!(sine >= min_distal_sine_)) {
    result.q.setZero();
    result.status = Reach::near_parallel;
    return result;
  }
  // J = A⁻¹B, A = [u1ᵀ; u2ᵀ], B = diag(l_pi·(e_i × u_i)).
  const double inverse_det = 1.0 / cross(u[0], u[1]);
  const double b0 = g_.proximal_m[0] * cross(e[0], u[0]) * inverse_det;
  const double b1 = g_.proximal_m[1] * cross(e[1], u[1]) * inverse_det;
  Mat2 J;
  J << b0 * u[1].y(), -b1 * u[0].y(), -b0 * u[1].x(), b1 * u[0].x();
  const double condition = condition_of(J);
  if (!(condition <= margin_.max_condition_number)) {
    result.q.setZero();
    result.status = Reach::ill_conditioned;
    return result;
  }
  result.status = Reach::ok;
  result.condition_number = condition;
  if (frame) {
    frame->jacobian = J;
    frame->proximal = e;
    frame->distal = u;
  }
  return result;
}

Mat2 FiveBar::jacobian_dot(const InverseFrame& f, const Vec2& qd) const noexcept {
  const Mat2& J = f.jacobian;
  Mat2 Jd;
  if (thesis_) {
    Jd << -J(1, 0) * qd.x(), -J(1, 1) * qd.y(), J(0, 0) * qd.x(), J(0, 1) * qd.y();
    return Jd;
  }
  const Vec2 pd = J * qd;
  Mat2 A, M;
  for (int i = 0; i < 2; ++i) {
    const Vec2& e = f.proximal[i];
    const Vec2& u = f.distal[i];
    const Vec2 e_perp(-e.y(), e.x()), u_perp(-u.y(), u.x());
    const double lp = g_.proximal_m[i];
    const double psi_dot = (pd - lp * qd[i] * e_perp).dot(u_perp) / g_.distal_m[i];
    A.row(i) = u.transpose();
    // Row i of Ḃ − ȦJ: Ḃ_ii on the diagonal, minus ψ̇_i·u_i⊥ᵀJ.
    M.row(i) = -psi_dot * (u_perp.transpose() * J);
    M(i, i) += lp * u.dot(e) * (psi_dot - qd[i]);
  }
  // A⁻¹ by the adjugate: det A = u1 × u2.
  const double inverse_det = 1.0 / (A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0));
  Mat2 A_inv;
  A_inv << A(1, 1) * inverse_det, -A(0, 1) * inverse_det, -A(1, 0) * inverse_det, A(0, 0) * inverse_det;
  return A_inv * M;
}

Mat2 FiveBar::jacobian(const Vec2& q) const noexcept {
  if (thesis_) {
    const double s1 = std::sin(q.x()), c1 = std::cos(q.x());
    const double s2 = std::sin(q.y()), c2 = std::cos(q.y());
    Mat2 J;
    J << -l_ * s1, -l_ * s2, l_ * c1, l_ * c2;
    return J;
  }
  Vec2 c;
  std::array<Vec2, 2> u;
  close_loop(q, c, u);
  const Vec2 l = links(q);
  const std::array<Vec2, 2> e{Vec2(std::cos(l.x()), std::sin(l.x())), Vec2(std::cos(l.y()), std::sin(l.y()))};
  const double inverse_det = 1.0 / cross(u[0], u[1]);
  const double b0 = g_.proximal_m[0] * cross(e[0], u[0]) * inverse_det;
  const double b1 = g_.proximal_m[1] * cross(e[1], u[1]) * inverse_det;
  Mat2 J;
  J << b0 * u[1].y(), -b1 * u[0].y(), -b0 * u[1].x(), b1 * u[0].x();
  return J;
}

Mat2 FiveBar::jacobian_dot(const Vec2& q, const Vec2& qd) const noexcept {
  if (thesis_) {
    const double s1 = std::sin(q.x()), c1 = std::cos(q.x());
    const double s2 = std::sin(q.y()), c2 = std::cos(q.y());
    Mat2 Jd;
    Jd << -l_ * c1 * qd.x(), -l_ * c2 * qd.y(), -l_ * s1 * qd.x(), -l_ * s2 * qd.y();
    return Jd;
  }
  InverseFrame f;
  Vec2 c;
  close_loop(q, c, f.distal);
  const Vec2 l = links(q);
  f.proximal = {Vec2(std::cos(l.x()), std::sin(l.x())), Vec2(std::cos(l.y()), std::sin(l.y()))};
  f.jacobian = jacobian(q);
  return jacobian_dot(f, qd);
}

double FiveBar::condition_number(const Vec2& q) const noexcept {
  if (thesis_) {
    const double c = std::abs(std::cos(q.x() - q.y()));
    if (c >= 1.0) return kInfinity;
    return std::sqrt((1.0 + c) / (1.0 - c));
  }
  return condition_of(jacobian(q));
}

PassiveAngles FiveBar::passive_angles(const Vec2& q) const noexcept {
  if (thesis_) return {q.y(), q.x()};
  Vec2 c;
  std::array<Vec2, 2> u;
  close_loop(q, c, u);
  return {std::atan2(u[0].y(), u[0].x()), std::atan2(u[1].y(), u[1].x())};
}

}  // namespace stiffpath::kinematics
