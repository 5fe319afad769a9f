// Junction speed limits: stops at G61 corners, and bounded velocity/acceleration steps everywhere else.
#include "stiffpath/motion/junction.hpp"

#include <algorithm>
#include <cmath>

namespace stiffpath::motion {

double turn_angle_rad(const Vec2& from, const Vec2& to) noexcept {
  const double cross = from.x() * to.y() - from.y() * to.x();
  return std::atan2(std::abs(cross), from.dot(to));
}

namespace {

// The speed bound of a junction whose acceleration step may use `acceleration_step_m_s2` (≤ j·τ)
// for its centripetal part.
double step_bounded_speed(const PathSegment& before, const SegmentLimits& before_limits, const PathSegment& after,
                          const SegmentLimits& after_limits, const MotionLimits& limits, const JunctionRules& rules,
                          double angle, double acceleration_step_m_s2) noexcept {
  const Vec2 t0 = end_tangent(before), t1 = start_tangent(after);
  double v = std::min(before_limits.max_velocity_m_s, after_limits.max_velocity_m_s);
  const double j = limits.max_jerk_m_s3, tau = rules.junction_time_s;
  const double velocity_step_per_speed = 2.0 * std::sin(0.5 * angle);
  if (velocity_step_per_speed > 0.0) v = std::min(v, j * tau * tau / velocity_step_per_speed);
  const Vec2 k0 = curvature_1_m(before) * left_normal(t0), k1 = curvature_1_m(after) * left_normal(t1);
  const double curvature_step = (k1 - k0).norm();
  if (curvature_step > 0.0) v = std::min(v, std::sqrt(acceleration_step_m_s2 / curvature_step));
  return std::max(v, 0.0);
}

}  // namespace

double junction_speed_limit(const PathSegment& before, const SegmentLimits& before_limits, const PathSegment& after,
                            const SegmentLimits& after_limits, const MotionLimits& limits,
                            const JunctionRules& rules) noexcept {
  if (before.kind == SegmentKind::dwell || after.kind == SegmentKind::dwell) return 0.0;
  const double angle = turn_angle_rad(end_tangent(before), start_tangent(after));
  if (angle > rules.corner_angle_rad && before.mode == JunctionMode::exact_stop) return 0.0;
  return step_bounded_speed(before, before_limits, after, after_limits, limits, rules, angle,
                            limits.max_jerk_m_s3 * rules.junction_time_s);
}

double tangent_junction_speed_limit(const PathSegment& before, const SegmentLimits& before_limits,
                                    const PathSegment& after, const SegmentLimits& after_limits,
                                    const MotionLimits& limits, const JunctionRules& rules,
                                    double tangential_acceleration_m_s2) noexcept {
  if (before.kind == SegmentKind::dwell || after.kind == SegmentKind::dwell) return 0.0;
  const double angle = turn_angle_rad(end_tangent(before), start_tangent(after));
  if (angle > rules.corner_angle_rad) return 0.0;
  const double budget = limits.max_jerk_m_s3 * rules.junction_time_s -
                        tangential_acceleration_m_s2 * 2.0 * std::sin(0.5 * angle);
  if (!(budget > 0.0)) return 0.0;
  return step_bounded_speed(before, before_limits, after, after_limits, limits, rules, angle, budget);
}

}  // namespace stiffpath::motion
