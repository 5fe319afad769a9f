// Per-segment limits: the feed cap on lines, and on arcs a split of a and j between tangential and normal terms.
#include "stiffpath/motion/segment_limits.hpp"

#include <algorithm>
#include <cmath>

namespace stiffpath::motion {

SegmentLimits segment_limits(const PathSegment& segment, const MotionLimits& limits) noexcept {
  if (segment.kind == SegmentKind::dwell) return {};
  const double a = segment.max_acceleration_m_s2 > 0.0 ? std::min(limits.max_acceleration_m_s2, segment.max_acceleration_m_s2)
                                                      : limits.max_acceleration_m_s2;
  const double j = limits.max_jerk_m_s3;
  SegmentLimits out{std::min(segment.feed_m_s, limits.max_velocity_m_s), a, j};
  const double kappa = std::abs(curvature_1_m(segment));
  if (segment.kind != SegmentKind::arc || kappa <= 0.0) return out;

  // min(F, sqrt(0.7a/κ), cbrt(0.3j/κ²)), taking the roots only where they may be below the cap.
  double v = out.max_velocity_m_s;
  const double acceleration_bound = arc_centripetal_acceleration_share * a / kappa;
  if (acceleration_bound < v * v) v = std::sqrt(acceleration_bound);
  const double jerk_bound = arc_centripetal_jerk_share * j / (kappa * kappa);
  if (jerk_bound < v * v * v) v = std::min(v, std::cbrt(jerk_bound));
  const double centripetal = v * v * kappa;
  double a_t = std::sqrt(std::max(a * a - centripetal * centripetal, 0.0));
  a_t = std::min(a_t, arc_normal_jerk_share * j / (3.0 * v * kappa));
  const double normal_jerk = 3.0 * v * kappa * a_t;
  out.max_velocity_m_s = v;
  out.max_acceleration_m_s2 = a_t;
  out.max_jerk_m_s3 = std::sqrt(j * j - normal_jerk * normal_jerk) - v * v * v * kappa * kappa;
  return out;
}

}  // namespace stiffpath::motion
