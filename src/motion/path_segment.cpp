// Geometry of line, arc and dwell segments: construction, point/tangent/curvature at an arc length.
#include "stiffpath/motion/path_segment.hpp"

#include <algorithm>
#include <cmath>

namespace stiffpath::motion {

PathSegment make_line(const Vec2& start_m, const Vec2& end_m) {
  PathSegment segment;
  segment.kind = SegmentKind::line;
  segment.start_m = start_m;
  segment.end_m = end_m;
  segment.length_m = (end_m - start_m).norm();
  return segment;
}

double distance_to_segment_m(const Vec2& p, const Vec2& a, const Vec2& b) noexcept {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

PathSegment carrying_attributes(PathSegment piece, const PathSegment& source) noexcept {
  piece.feed_m_s = source.feed_m_s;
  piece.power = source.power;
  piece.dynamic_power = source.dynamic_power;
  piece.blend_tolerance_m = source.blend_tolerance_m;
  piece.merge_tolerance_m = source.merge_tolerance_m;
  piece.max_acceleration_m_s2 = source.max_acceleration_m_s2;
  piece.line = source.line;
  piece.rapid = source.rapid;
  piece.laser_on = source.laser_on;
  piece.mode = source.mode;
  return piece;
}

PathSegment make_arc(const Vec2& start_m, const Vec2& end_m, const Vec2& center_m, double sweep_rad) {
  PathSegment segment;
  segment.kind = SegmentKind::arc;
  segment.start_m = start_m;
  segment.end_m = end_m;
  segment.center_m = center_m;
  const Vec2 r = start_m - center_m;
  segment.radius_m = r.norm();
  segment.start_angle_rad = std::atan2(r.y(), r.x());
  segment.sweep_rad = sweep_rad;
  segment.length_m = segment.radius_m * std::abs(sweep_rad);
  return segment;
}

PathSegment make_dwell(const Vec2& point_m, double duration_s) {
  PathSegment segment;
  segment.kind = SegmentKind::dwell;
  segment.start_m = point_m;
  segment.end_m = point_m;
  segment.dwell_s = duration_s;
  segment.feed_m_s = 0.0;
  return segment;
}

double curvature_1_m(const PathSegment& segment) noexcept {
  if (segment.kind != SegmentKind::arc || segment.radius_m <= 0.0) return 0.0;
  return std::copysign(1.0 / segment.radius_m, segment.sweep_rad);
}

PathPoint point_at(const PathSegment& segment, double s_m) noexcept {
  PathPoint point;
  switch (segment.kind) {
    case SegmentKind::dwell:
      point.position_m = segment.start_m;
      return point;
    case SegmentKind::line: {
      point.tangent = segment.length_m > 0.0 ? Vec2((segment.end_m - segment.start_m) / segment.length_m)
                                             : Vec2::UnitX();
      if (!(s_m < segment.length_m)) {
        point.position_m = segment.end_m;
      } else {
        point.position_m = segment.start_m + std::max(s_m, 0.0) * point.tangent;
      }
      return point;
    }
    case SegmentKind::arc: {
      const double fraction = segment.length_m > 0.0 ? std::clamp(s_m / segment.length_m, 0.0, 1.0) : 0.0;
      const double angle = segment.start_angle_rad + fraction * segment.sweep_rad;
      const Vec2 radial(std::cos(angle), std::sin(angle));
      point.position_m = fraction >= 1.0   ? segment.end_m
                         : fraction <= 0.0 ? segment.start_m
                                           : Vec2(segment.center_m + segment.radius_m * radial);
      point.tangent = segment.sweep_rad >= 0.0 ? left_normal(radial) : Vec2(-left_normal(radial));
      point.curvature_1_m = curvature_1_m(segment);
      return point;
    }
  }
  return point;
}

double power_at(const PathSegment& segment, double speed_m_s) noexcept {
  if (!segment.laser_on) return 0.0;
  if (!segment.dynamic_power) return segment.power;
  if (!(segment.feed_m_s > 0.0) || !(speed_m_s > 0.0)) return 0.0;  // at rest M4 does not fire
  return segment.power * std::min(1.0, speed_m_s / segment.feed_m_s);
}

Vec2 start_tangent(const PathSegment& segment) noexcept { return point_at(segment, 0.0).tangent; }

Vec2 end_tangent(const PathSegment& segment) noexcept { return point_at(segment, segment.length_m).tangent; }

}  // namespace stiffpath::motion
