// Mechanism contract: the parts shared by every mechanism (velocity/acceleration level, throwing IK).
#include "stiffpath/kinematics/mechanism.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::kinematics {

const char* describe(Reach reach) noexcept {
  switch (reach) {
    case Reach::ok: return "reachable";
    case Reach::not_finite: return "coordinate is not a finite number";
    case Reach::near_stretched: return "too close to the stretched-out singularity (|AC| -> l_p + l_d)";
    case Reach::near_origin: return "too close to the folded singularity (|AC| -> |l_p - l_d|)";
    case Reach::near_parallel: return "too close to the parallel singularity (the distal links almost collinear)";
    case Reach::other_assembly: return "only reachable in the other assembly mode (across the parallel singularity)";
    case Reach::ill_conditioned: return "Jacobian is ill-conditioned (condition number above the margin)";
  }
  return "unknown";
}

double Mechanism::condition_number(const Vec2& q) const noexcept {
  const Eigen::JacobiSVD<Mat2> svd(jacobian(q));
  const auto& s = svd.singularValues();
  if (s(1) <= 0.0) return std::numeric_limits<double>::infinity();
  return s(0) / s(1);
}

std::string Mechanism::explain(const Vec2& p) const {
  const Reach reach = check_reach(p);
  return reach == Reach::ok ? std::string() : describe(reach);
}

Vec2 Mechanism::inverse(const Vec2& p) const {
  const InverseResult r = solve_inverse(p);
  if (r.status != Reach::ok) {
    throw Error(fmt::format("point (x = {:.4f} mm, y = {:.4f} mm) refused: {}", units::m_to_mm(p.x()),
                            units::m_to_mm(p.y()), explain(p)));
  }
  return r.q;
}

Vec2 Mechanism::joint_velocity(const Vec2& q, const Vec2& pd) const noexcept {
  return jacobian(q).inverse() * pd;
}

Vec2 Mechanism::acceleration(const Vec2& q, const Vec2& qd, const Vec2& qdd) const noexcept {
  return jacobian(q) * qdd + jacobian_dot(q, qd) * qd;
}

Vec2 Mechanism::joint_acceleration(const Vec2& q, const Vec2& qd, const Vec2& pdd) const noexcept {
  return jacobian(q).inverse() * (pdd - jacobian_dot(q, qd) * qd);
}

}  // namespace stiffpath::kinematics
