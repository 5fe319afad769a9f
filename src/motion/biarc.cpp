// Biarcs: the arc from a point and tangent to a point, and two of them joining two tangents.
#include "stiffpath/motion/biarc.hpp"

#include <cmath>
#include <numbers>

namespace stiffpath::motion {

namespace {
constexpr double straight_rad = 5e-8;  // half-turns below this are lines
constexpr double max_piece_sweep_rad = 0.5 * std::numbers::pi;

double cross(const Vec2& a, const Vec2& b) noexcept { return a.x() * b.y() - a.y() * b.x(); }
}  // namespace

std::optional<PathSegment> arc_from_tangent(const Vec2& from_m, const Vec2& tangent, const Vec2& to_m) noexcept {
  const Vec2 chord = to_m - from_m;
  const double along = tangent.dot(chord), across = cross(tangent, chord);
  if (!(along > 0.0) || !(chord.squaredNorm() > 0.0)) return std::nullopt;
  const double half_turn = std::atan2(across, along);  // angle from the tangent to the chord
  if (std::abs(half_turn) < straight_rad) return make_line(from_m, to_m);
  const double curvature = 2.0 * across / chord.squaredNorm();
  const Vec2 center = from_m + left_normal(tangent) / curvature;
  return make_arc(from_m, to_m, center, 2.0 * half_turn);
}

std::optional<std::array<PathSegment, 2>> biarc(const Vec2& p0_m, const Vec2& t0, const Vec2& p1_m,
                                                const Vec2& t1) noexcept {
  const Vec2 v = p1_m - p0_m;
  const double w = v.squaredNorm(), b = v.dot(t0 + t1), c = (t0 - t1).squaredNorm();
  if (!(w > 0.0) || !(b > 0.0)) return std::nullopt;
  const double d = w / (b + std::sqrt(b * b + c * w));
  const Vec2 control0 = p0_m + d * t0, control1 = p1_m - d * t1;
  const Vec2 joint = 0.5 * (control0 + control1);
  const Vec2 between = control1 - control0;
  const Vec2 joint_tangent = between.squaredNorm() > 0.0 ? Vec2(between.normalized()) : Vec2(v.normalized());
  const std::optional<PathSegment> first = arc_from_tangent(p0_m, t0, joint);
  const std::optional<PathSegment> second = arc_from_tangent(joint, joint_tangent, p1_m);
  if (!first || !second) return std::nullopt;
  if (std::abs(first->sweep_rad) > max_piece_sweep_rad || std::abs(second->sweep_rad) > max_piece_sweep_rad) {
    return std::nullopt;
  }
  return std::array<PathSegment, 2>{*first, *second};
}

}  // namespace stiffpath::motion
