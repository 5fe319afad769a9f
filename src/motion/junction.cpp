// Junction speed limits: stops at G61 corners, and bounded velocity/acceleration steps everywhere else.
#include "stiffpath/motion/junction.hpp"

#include <algorithm>
#include <cmath>

namespace stiffpath::motion {

const char* to_string(SpeedLimit limit) noexcept {
  switch (limit) {
    case SpeedLimit::none: return "none";
    case SpeedLimit::rest: return "rest";
    case SpeedLimit::dwell: return "dwell";
    case SpeedLimit::exact_stop: return "exact_stop";
    case SpeedLimit::corner: return "corner";
    case SpeedLimit::curvature_step: return "curvature_step";
    case SpeedLimit::arc_speed: return "arc_speed";
    case SpeedLimit::feed: return "feed";
  }
  return "unknown";
}

const char* describe(SpeedLimit limit) noexcept {
  switch (limit) {
    case SpeedLimit::none: return "nothing";
    case SpeedLimit::rest: return "start and end at rest";
    case SpeedLimit::dwell: return "dwells and program stops";
    case SpeedLimit::exact_stop: return "stops at G61 corners";
    case SpeedLimit::corner: return "sharp corners, not rounded (2v*sin(phi/2) <= j*tau^2)";
    case SpeedLimit::curvature_step: return "curvature steps (v^2*dk <= j*tau)";
    case SpeedLimit::arc_speed: return "arcs' speed caps (centripetal a, j)";
    case SpeedLimit::feed: return "changes of the programmed feed";
  }
  return "unknown";
}

double turn_angle_rad(const Vec2& from, const Vec2& to) noexcept {
  const double cross = from.x() * to.y() - from.y() * to.x();
  return std::atan2(std::abs(cross), from.dot(to));
}

namespace {

// Unit tangent at a segment's start or end without trigonometry: a line's chord, or an arc's radius
// turned by ±90°.
Vec2 tangent_at(const PathSegment& segment, bool at_end) noexcept {
  if (segment.kind == SegmentKind::line && segment.length_m > 0.0) {
    return (segment.end_m - segment.start_m) / segment.length_m;
  }
  if (segment.kind == SegmentKind::arc) {
    const Vec2 radial = (at_end ? segment.end_m : segment.start_m) - segment.center_m;
    const double r = radial.norm();
    if (r > 0.0) return segment.sweep_rad >= 0.0 ? left_normal(radial / r) : Vec2(-left_normal(radial / r));
  }
  return at_end ? end_tangent(segment) : start_tangent(segment);
}

// The speed bound of a junction whose acceleration step may use `acceleration_step_m_s2` (≤ j·τ)
// for its centripetal part. The velocity step per speed is |t₁ − t₀| = 2·sin(φ/2).
double step_bounded_speed(const PathSegment& before, const SegmentLimits& before_limits, const PathSegment& after,
                          const SegmentLimits& after_limits, const MotionLimits& limits, const JunctionRules& rules,
                          const Vec2& t0, const Vec2& t1, double acceleration_step_m_s2, SpeedLimit* cause = nullptr) noexcept {
  const bool before_lower = before_limits.max_velocity_m_s <= after_limits.max_velocity_m_s;
  double v = std::min(before_limits.max_velocity_m_s, after_limits.max_velocity_m_s);
  SpeedLimit bound = SpeedLimit::none;
  if (cause != nullptr) {  // which cap: an arc's below its feed, or a feed
    const PathSegment& lower = before_lower ? before : after;
    bound = v < std::min(lower.feed_m_s, limits.max_velocity_m_s) ? SpeedLimit::arc_speed : SpeedLimit::feed;
  }
  const double j = limits.max_jerk_m_s3, tau = rules.junction_time_s;
  const double velocity_step_per_speed = (t1 - t0).norm();
  if (velocity_step_per_speed > 0.0 && j * tau * tau / velocity_step_per_speed < v) {
    v = j * tau * tau / velocity_step_per_speed;
    bound = SpeedLimit::corner;
  }
  const Vec2 k0 = curvature_1_m(before) * left_normal(t0), k1 = curvature_1_m(after) * left_normal(t1);
  const double curvature_step = (k1 - k0).norm();
  if (curvature_step > 0.0 && std::sqrt(acceleration_step_m_s2 / curvature_step) < v) {
    v = std::sqrt(acceleration_step_m_s2 / curvature_step);
    bound = SpeedLimit::curvature_step;
  }
  if (cause != nullptr) *cause = bound;
  return std::max(v, 0.0);
}

// A turn by more than the corner angle φ_c: |t₁ − t₀| = 2·sin(φ/2) > 2·sin(φ_c/2). For the small
// corner angles in use the series c − c³/24 + c⁵/1920 is exact to rounding (next term c⁷/322560).
bool is_corner(const Vec2& t0, const Vec2& t1, const JunctionRules& rules) noexcept {
  const double c = rules.corner_angle_rad, c2 = c * c;
  const double chord = c <= 0.01 ? c * (1.0 - c2 / 24.0 * (1.0 - c2 / 80.0)) : 2.0 * std::sin(0.5 * c);
  return (t1 - t0).norm() > chord;
}

}  // namespace

double junction_speed_limit(const PathSegment& before, const SegmentLimits& before_limits, const PathSegment& after,
                            const SegmentLimits& after_limits, const MotionLimits& limits,
                            const JunctionRules& rules, SpeedLimit* cause) noexcept {
  if (before.kind == SegmentKind::dwell || after.kind == SegmentKind::dwell) {
    if (cause != nullptr) *cause = SpeedLimit::dwell;
    return 0.0;
  }
  const Vec2 t0 = tangent_at(before, true), t1 = tangent_at(after, false);
  if (before.mode == JunctionMode::exact_stop && is_corner(t0, t1, rules)) {
    if (cause != nullptr) *cause = SpeedLimit::exact_stop;
    return 0.0;
  }
  return step_bounded_speed(before, before_limits, after, after_limits, limits, rules, t0, t1,
                            limits.max_jerk_m_s3 * rules.junction_time_s, cause);
}

double tangent_junction_speed_limit(const PathSegment& before, const SegmentLimits& before_limits,
                                    const PathSegment& after, const SegmentLimits& after_limits,
                                    const MotionLimits& limits, const JunctionRules& rules,
                                    double tangential_acceleration_m_s2) noexcept {
  if (before.kind == SegmentKind::dwell || after.kind == SegmentKind::dwell) return 0.0;
  const Vec2 t0 = tangent_at(before, true), t1 = tangent_at(after, false);
  if (is_corner(t0, t1, rules)) return 0.0;
  const double budget = limits.max_jerk_m_s3 * rules.junction_time_s - tangential_acceleration_m_s2 * (t1 - t0).norm();
  if (!(budget > 0.0)) return 0.0;
  return step_bounded_speed(before, before_limits, after, after_limits, limits, rules, t0, t1, budget);
}

}  // namespace stiffpath::motion
