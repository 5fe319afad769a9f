// Five-bar kinematics, thesis eqs. 2.1–2.2, with analytic Jacobian, J̇ and singularity margins.
#include "stiffpath/kinematics/five_bar.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stiffpath/core/error.hpp"

namespace stiffpath::kinematics {

FiveBar::FiveBar(double link_length_m, SingularityMargin margin)
    : l_(link_length_m), inverse_2l_(1.0 / (2.0 * link_length_m)), margin_(margin) {
  if (!(std::isfinite(l_) && l_ > 0.0)) throw Error("five-bar link length must be positive and finite");
  if (!(margin_.min_distance_m >= 0.0 && margin_.min_distance_m < l_)) {
    throw Error("singularity margin min_distance must lie in [0, l)");
  }
  if (!(margin_.max_condition_number > 1.0)) throw Error("singularity margin max_condition_number must exceed 1");
}

Vec2 FiveBar::forward(const Vec2& q) const noexcept {
  return {l_ * (std::cos(q.x()) + std::cos(q.y())), l_ * (std::sin(q.x()) + std::sin(q.y()))};
}

namespace {
// κ = max(tan η, cot η) from cos η = c and sin η = s (σ1,2 = l·√2·{cos η, sin η}).
double condition_from(double c, double s) noexcept {
  if (c <= 0.0 || s <= 0.0) return std::numeric_limits<double>::infinity();
  return std::max(s / c, c / s);
}
}  // namespace

double FiveBar::condition_number_at_radius(double r) const noexcept {
  const double c = std::abs(r) / (2.0 * l_);
  if (c >= 1.0) return std::numeric_limits<double>::infinity();
  return condition_from(c, std::sqrt(1.0 - c * c));
}

Reach FiveBar::check_reach(const Vec2& p) const noexcept {
  if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return Reach::not_finite;
  const double r = p.norm();
  if (r > 2.0 * l_ - margin_.min_distance_m) return Reach::near_stretched;
  if (r < margin_.min_distance_m) return Reach::near_origin;
  if (!(condition_number_at_radius(r) <= margin_.max_condition_number)) return Reach::ill_conditioned;
  return Reach::ok;
}

InverseResult FiveBar::solve_inverse(const Vec2& p) const noexcept {
  Mat2 unused;
  return solve_inverse(p, unused);
}

InverseResult FiveBar::solve_inverse(const Vec2& p, Mat2& jacobian) const noexcept {
  // check_reach() written out so that r, cos η and sin η are computed once, and with two divisions
  // instead of six: this is the real-time path.
  InverseResult result;
  result.condition_number = std::numeric_limits<double>::infinity();
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
  // κ = max(tan η, cot η) = max(c, s) / min(c, s): the same number as condition_from() with one division.
  const double condition = c_eta >= 1.0 || c_eta <= 0.0 || s_eta <= 0.0 ? std::numeric_limits<double>::infinity()
                                                                         : std::max(c_eta, s_eta) / std::min(c_eta, s_eta);
  if (!(condition <= margin_.max_condition_number)) {
    result.status = Reach::ill_conditioned;
    return result;
  }
  result.status = Reach::ok;
  const double inverse_r = 1.0 / r;
  const double c_phi = p.x() * inverse_r, s_phi = p.y() * inverse_r;
  const double phi = std::atan2(p.y(), p.x());
  const double eta = std::acos(c_eta);
  result.q = {phi + eta, phi - eta};
  result.condition_number = condition;
  // cos/sin of φ ± η by the angle-sum identities.
  const double c1 = c_phi * c_eta - s_phi * s_eta, s1 = s_phi * c_eta + c_phi * s_eta;
  const double c2 = c_phi * c_eta + s_phi * s_eta, s2 = s_phi * c_eta - c_phi * s_eta;
  jacobian << -l_ * s1, -l_ * s2, l_ * c1, l_ * c2;
  return result;
}

Mat2 FiveBar::jacobian(const Vec2& q) const noexcept {
  const double s1 = std::sin(q.x()), c1 = std::cos(q.x());
  const double s2 = std::sin(q.y()), c2 = std::cos(q.y());
  Mat2 J;
  J << -l_ * s1, -l_ * s2, l_ * c1, l_ * c2;
  return J;
}

Mat2 FiveBar::jacobian_dot(const Vec2& q, const Vec2& qd) const noexcept {
  const double s1 = std::sin(q.x()), c1 = std::cos(q.x());
  const double s2 = std::sin(q.y()), c2 = std::cos(q.y());
  Mat2 Jd;
  Jd << -l_ * c1 * qd.x(), -l_ * c2 * qd.y(), -l_ * s1 * qd.x(), -l_ * s2 * qd.y();
  return Jd;
}

double FiveBar::condition_number(const Vec2& q) const noexcept {
  const double c = std::abs(std::cos(q.x() - q.y()));
  if (c >= 1.0) return std::numeric_limits<double>::infinity();
  return std::sqrt((1.0 + c) / (1.0 - c));
}

PassiveAngles FiveBar::passive_angles(const Vec2& q) noexcept { return {q.y(), q.x()}; }

}  // namespace stiffpath::kinematics
