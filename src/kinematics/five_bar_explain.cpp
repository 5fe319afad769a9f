// Why the five-bar refuses a point, in words with the arm and the numbers involved.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "stiffpath/kinematics/five_bar.hpp"

namespace stiffpath::kinematics {

namespace {
constexpr double kDeg = 180.0 / std::numbers::pi;
const char* side(int i) { return i == 0 ? "left" : "right"; }
}  // namespace

std::string FiveBar::explain(const Vec2& p) const {
  const InverseResult r = solve_inverse(p);
  if (r.status == Reach::ok) return {};
  const double mm = 1e3;
  switch (r.status) {
    case Reach::near_stretched:
      for (int i = 0; i < 2; ++i) {
        const double d = (p - g_.actuator_m[i]).norm();
        if (d > arm_[i].outer_m || thesis_) {
          return fmt::format("too close to the stretched-out singularity: the {} arm would reach {:.3f} mm from its "
                             "actuator, beyond l_p + l_d - margin = {:.3f} mm",
                             side(i), d * mm, arm_[i].outer_m * mm);
        }
      }
      break;
    case Reach::near_origin:
      for (int i = 0; i < 2; ++i) {
        const double d = (p - g_.actuator_m[i]).norm();
        if (!(d >= arm_[i].inner_m) || thesis_) {
          return fmt::format("too close to the folded singularity: the {} arm would reach only {:.3f} mm from its "
                             "actuator, within |l_p - l_d| + margin = {:.3f} mm",
                             side(i), d * mm, arm_[i].inner_m * mm);
        }
      }
      break;
    case Reach::near_parallel:
    case Reach::other_assembly: {
      // The distal directions of the working mode, computed plainly (this is not the real-time path).
      std::array<Vec2, 2> u;
      for (int i = 0; i < 2; ++i) {
        const Vec2 d = p - g_.actuator_m[i];
        const double dist = d.norm(), lp = g_.proximal_m[i], ld = g_.distal_m[i];
        const double alpha = std::acos(std::clamp((dist * dist + lp * lp - ld * ld) / (2 * dist * lp), -1.0, 1.0));
        const double theta = std::atan2(d.y(), d.x()) + g_.elbows[i] * alpha;
        u[i] = (d - lp * Vec2(std::cos(theta), std::sin(theta))) / ld;
      }
      const double sine = u[0].x() * u[1].y() - u[0].y() * u[1].x();
      const double angle = std::atan2(std::abs(sine), u[0].dot(u[1])) * kDeg;
      if (r.status == Reach::near_parallel) {
        return fmt::format("too close to the parallel singularity: the distal links meet at {:.3f} deg, closer than "
                           "{:.3f} deg to collinear",
                           angle, margin_.min_distal_angle_rad * kDeg);
      }
      return fmt::format("only reachable in the other assembly mode (u_left x u_right = {:+.4f}, the robot's "
                         "assembly is {:+d}): it would have to pass through the parallel singularity",
                         sine, g_.assembly);
    }
    case Reach::ill_conditioned: {
      InverseFrame f;
      const FiveBar lenient(g_, {margin_.min_distance_m, 1e300, margin_.min_distal_angle_rad}, angle_floor_);
      const InverseResult loose = lenient.solve_inverse(p, f);
      return fmt::format("Jacobian is ill-conditioned: condition number {:.3f} above the margin's {:.3f}",
                         loose.condition_number, margin_.max_condition_number);
    }
    case Reach::not_finite:
    case Reach::ok: break;
  }
  return describe(r.status);
}

}  // namespace stiffpath::kinematics
