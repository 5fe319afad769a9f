// Corner blending for G64: tangent fillet arcs between lines, trimming each line by at most half its length.
#include "stiffpath/motion/corner_blend.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "stiffpath/motion/junction.hpp"

namespace stiffpath::motion {

std::optional<CornerFillet> corner_fillet(const Vec2& corner_m, const Vec2& in, const Vec2& out, double tolerance_m,
                                          double max_trim_m) noexcept {
  const double angle = turn_angle_rad(in, out);
  if (!(tolerance_m > 0.0) || !(max_trim_m > 0.0) || angle <= 0.0 || angle > std::numbers::pi - 1e-6) {
    return std::nullopt;
  }
  // Half-angle functions from cos φ = in·out and sin φ = |in × out|, without cancellation:
  // cos(φ/2) = sqrt((1 + cos φ)/2), tan(φ/2) = sin φ/(1 + cos φ), 1 − cos(φ/2) = sin²(φ/2)/(1 + cos(φ/2)).
  const double cos_angle = in.dot(out), sin_angle = std::abs(in.x() * out.y() - in.y() * out.x());
  const double cos_half = std::sqrt(0.5 * (1.0 + cos_angle)), tan_half = sin_angle / (1.0 + cos_angle);
  const double sin_half = tan_half * cos_half;
  // Distance from the corner to the arc's midpoint is r·(1/cos(φ/2) − 1); solve for the largest r.
  const double radius_for_tolerance = tolerance_m * cos_half * (1.0 + cos_half) / (sin_half * sin_half);
  const double trim = std::min(radius_for_tolerance * tan_half, max_trim_m);
  CornerFillet fillet;
  fillet.trim_m = trim;
  fillet.radius_m = trim / tan_half;
  fillet.entry_m = corner_m - trim * in;
  fillet.exit_m = corner_m + trim * out;
  const bool left = in.x() * out.y() - in.y() * out.x() > 0.0;
  fillet.center_m = fillet.entry_m + (left ? 1.0 : -1.0) * fillet.radius_m * left_normal(in);
  fillet.sweep_rad = left ? angle : -angle;
  return fillet;
}

std::optional<PathSegment> arc_absorbing_line(const Vec2& line_start_m, const Vec2& in, const CornerFillet& fillet,
                                              double max_kink_rad) noexcept {
  // The circle through the line's start and the fillet's exit, tangent at the exit: its centre lies
  // on the exit's normal at ρ = |p − x|² / (2 (p − x)·n).
  const double side = fillet.sweep_rad > 0.0 ? 1.0 : -1.0;
  const Vec2 exit_tangent = (fillet.exit_m - fillet.center_m).norm() > 0.0
                                ? Vec2(side * left_normal(fillet.exit_m - fillet.center_m).normalized())
                                : Vec2(in);
  const Vec2 normal = side * left_normal(exit_tangent);  // towards the centre
  const Vec2 chord = line_start_m - fillet.exit_m;
  const double along = chord.dot(normal);
  if (!(along > 0.0)) return std::nullopt;
  const double radius = chord.squaredNorm() / (2.0 * along);
  const Vec2 center = fillet.exit_m + radius * normal;
  const Vec2 from = line_start_m - center, to = fillet.exit_m - center;
  const double sweep = std::atan2(from.x() * to.y() - from.y() * to.x(), from.dot(to));
  if (!(sweep * side > 0.0)) return std::nullopt;
  // The start tangent is the radius at the start turned by ±90°; the kink is its angle to `in`.
  const Vec2 start_direction = side * left_normal(from / from.norm());
  if (!(turn_angle_rad(in, start_direction) <= max_kink_rad)) return std::nullopt;
  return make_arc(line_start_m, fillet.exit_m, center, sweep);
}

CornerBlender::CornerBlender(PathSource& source, double corner_angle_rad, bool fit_chords)
    : fitter_(fit_chords ? std::make_unique<ChordFitter>(source) : nullptr),
      source_(fitter_ ? *fitter_ : source), corner_angle_rad_(corner_angle_rad), corner_chord_(2.0 * std::sin(0.5 * corner_angle_rad)) {}

std::optional<PathSegment> CornerBlender::next() {
  while (ready_.empty()) {
    if (exhausted_) {
      if (!held_) return std::nullopt;
      ready_.push_back(*held_);
      held_.reset();
      break;
    }
    std::optional<PathSegment> incoming = source_.next();
    if (!incoming) {
      exhausted_ = true;
      continue;
    }
    if (!held_) {
      held_ = *incoming;
      held_length_m_ = incoming->length_m;
      continue;
    }
    PathSegment& a = *held_;
    PathSegment b = *incoming;
    const bool blendable = a.kind == SegmentKind::line && b.kind == SegmentKind::line &&
                           a.mode == JunctionMode::blend && a.laser_on == b.laser_on && a.rapid == b.rapid;
    const Vec2 in = end_tangent(a), out = start_tangent(b);
    std::optional<CornerFillet> fillet;
    if (blendable && (out - in).norm() > corner_chord_) {  // |out − in| = 2·sin(φ/2)
      fillet = corner_fillet(a.end_m, in, out, a.blend_tolerance_m, 0.5 * std::min(held_length_m_, b.length_m));
    }
    if (fillet) {
      a.end_m = fillet->entry_m;
      a.length_m = (a.end_m - a.start_m).norm();
      // If the two blends of a line leave (almost) nothing of it, the arc starts where the line did.
      std::optional<PathSegment> absorbing =
          a.length_m <= 0.1 * a.blend_tolerance_m ? arc_absorbing_line(a.start_m, in, *fillet, 0.25 * corner_angle_rad_)
                                                  : std::nullopt;
      const bool keep_line = !absorbing && a.length_m >= shortest_segment_m;
      PathSegment arc = absorbing ? *absorbing
                                  : make_arc(keep_line ? fillet->entry_m : a.start_m, fillet->exit_m, fillet->center_m,
                                             fillet->sweep_rad);
      arc.feed_m_s = std::min(a.feed_m_s, b.feed_m_s);
      arc.power = a.power;
      arc.dynamic_power = a.dynamic_power;
      arc.blend_tolerance_m = a.blend_tolerance_m;
      arc.line = a.line;
      arc.rapid = a.rapid;
      arc.laser_on = a.laser_on;
      arc.mode = a.mode;
      if (keep_line) ready_.push_back(a);
      ready_.push_back(arc);
      b.start_m = fillet->exit_m;
      b.length_m = (b.end_m - b.start_m).norm();
    } else {
      ready_.push_back(a);
    }
    held_length_m_ = incoming->length_m;
    held_ = b;
  }
  PathSegment out = ready_.front();
  ready_.pop_front();
  return out;
}

}  // namespace stiffpath::motion
