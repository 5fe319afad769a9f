// Corner blending for G64: tangent fillets (or biarcs) between lines, trimming each by at most half its length.
#include "stiffpath/motion/corner_blend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "stiffpath/motion/biarc.hpp"
#include "stiffpath/motion/junction.hpp"
#include "stiffpath/motion/segment_limits.hpp"

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

namespace {
// A piece of a blend between lines a and b: a's attributes with the lower of both feeds.
PathSegment blend_piece(const PathSegment& piece, const PathSegment& a, const PathSegment& b) noexcept {
  PathSegment out = carrying_attributes(piece, a);
  out.feed_m_s = std::min(a.feed_m_s, b.feed_m_s);
  return out;
}

// What two blends may leave of a line for the second one's arc to absorb it (a tenth of P).
double absorbed_line_m(double tolerance_m) noexcept { return 0.1 * tolerance_m; }
}  // namespace

std::optional<std::array<PathSegment, 2>> corner_biarc(const Vec2& corner_m, const Vec2& in, const Vec2& out,
                                                       double t_in_m, double t_out_m, double tolerance_m) noexcept {
  if (!(t_in_m > 0.0) || !(t_out_m > 0.0) || !(tolerance_m > 0.0)) return std::nullopt;
  const Vec2 entry = corner_m - t_in_m * in, exit = corner_m + t_out_m * out;
  const std::optional<std::array<PathSegment, 2>> pieces = biarc(entry, in, exit, out);
  if (!pieces) return std::nullopt;
  // The distance to the two lines, min(d_in, d_out), is smooth along each piece except where the
  // piece crosses the corner's bisector (d_in = d_out, a ridge): that point is found by bisection to
  // h/1024 and checked with the distance's rise over that width (at most sin φ per unit length: the
  // pieces' tangents lie between the two lines' directions); elsewhere a distance to a line varies
  // along an arc with |d''| ≤ κ, so between two checked points it exceeds the higher by at most κ·h²/8.
  const Vec2 bisector = out - in;
  const double slope = std::sin(std::min(turn_angle_rad(in, out), 0.5 * std::numbers::pi));
  auto deviation = [&](const Vec2& p) {
    return std::min(distance_to_segment_m(p, entry, corner_m), distance_to_segment_m(p, corner_m, exit));
  };
  auto side = [&](const Vec2& p) { return (p - corner_m).x() * bisector.y() - (p - corner_m).y() * bisector.x(); };
  constexpr int intervals = 8;
  for (const PathSegment& piece : *pieces) {
    const double h = piece.length_m / intervals;
    const double curvature = piece.kind == SegmentKind::arc ? 1.0 / piece.radius_m : 0.0;
    const double rise = curvature * h * h / 8.0;
    double previous_side = side(piece.start_m);
    for (int m = 0; m <= intervals; ++m) {
      const Vec2 p = point_at(piece, h * m).position_m;
      if (!(deviation(p) + rise <= tolerance_m)) return std::nullopt;
      const double this_side = side(p);
      if (m > 0 && (this_side < 0.0) != (previous_side < 0.0)) {  // the ridge lies in this interval
        double lo = h * (m - 1), hi = h * m;
        for (int k = 0; k < 10; ++k) {
          const double mid = 0.5 * (lo + hi);
          ((side(point_at(piece, mid).position_m) < 0.0) == (previous_side < 0.0) ? lo : hi) = mid;
        }
        const double ridge = deviation(point_at(piece, 0.5 * (lo + hi)).position_m) + slope * 0.5 * (hi - lo);
        if (!(ridge + rise <= tolerance_m)) return std::nullopt;
      }
      previous_side = this_side;
    }
  }
  return pieces;
}

CornerBlender::CornerBlender(PathSource& source, double corner_angle_rad, bool fit_chords)
    : fitter_(fit_chords ? std::make_unique<ChordFitter>(source) : nullptr),
      source_(fitter_ ? *fitter_ : source),
      corner_angle_rad_(corner_angle_rad),
      corner_chord_(2.0 * std::sin(0.5 * corner_angle_rad)) {}

CornerBlender::CornerBlender(PathSource& source, double corner_angle_rad, ChordFitting fitting, const CornerSpeedModel& model)
    : fitter_(fitting != ChordFitting::none ? std::make_unique<ChordFitter>(source, fitting == ChordFitting::merged) : nullptr),
      source_(fitter_ ? *fitter_ : source),
      corner_angle_rad_(corner_angle_rad),
      corner_chord_(2.0 * std::sin(0.5 * corner_angle_rad)),
      model_(model) {}

double CornerBlender::speed_bound_at_held_start() const noexcept {
  if (!(held_start_arc_radius_m_ > 0.0)) return held_start_speed_m_s_;
  const MotionLimits& l = model_->limits;
  PathSegment arc = make_arc(Vec2(held_start_arc_radius_m_, 0.0), Vec2(0.0, held_start_arc_radius_m_), Vec2::Zero(),
                             0.5 * std::numbers::pi);
  arc.feed_m_s = held_start_arc_feed_m_s_;
  const double step = std::sqrt(l.max_jerk_m_s3 * model_->junction_time_s * held_start_arc_radius_m_);
  return std::min({held_start_speed_m_s_, step, segment_limits(arc, l).max_velocity_m_s});
}

std::optional<CornerFillet> CornerBlender::chosen_fillet(const CornerFillet& full, const PathSegment& b, const Vec2& in,
                                                         const Vec2& out, double tolerance_m, double max_trim_m) {
  const PathSegment& a = *held_;
  const MotionLimits& limits = model_->limits;
  const double cap_in = std::min(a.feed_m_s, limits.max_velocity_m_s), cap_out = std::min(b.feed_m_s, limits.max_velocity_m_s);
  const CornerInput corner{turn_angle_rad(in, out), full.trim_m, a.length_m, b.length_m, speed_bound_at_held_start(),
                           cap_in, cap_out, std::min(a.feed_m_s, b.feed_m_s)};
  const CornerChoice choice = choose_corner(corner, *model_);
  next_start_speed_m_s_ = choice.pass_speed_m_s;
  if (!(choice.trim_m > 0.0)) return std::nullopt;
  if (choice.trim_m >= full.trim_m) return full;
  return corner_fillet(a.end_m, in, out, tolerance_m, std::min(max_trim_m, choice.trim_m));
}

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
      held_blended_ = false;
      held_start_speed_m_s_ = 0.0;  // the program starts at rest
      held_start_arc_radius_m_ = 0.0;
      continue;
    }
    PathSegment& a = *held_;
    PathSegment b = *incoming;
    const bool blendable = a.kind == SegmentKind::line && b.kind == SegmentKind::line &&
                           a.mode == JunctionMode::blend && a.laser_on == b.laser_on && a.rapid == b.rapid;
    const Vec2 in = end_tangent(a), out = start_tangent(b);
    std::optional<CornerFillet> fillet;
    const double max_trim = 0.5 * std::min(held_length_m_, b.length_m);
    const double tolerance = std::min(a.blend_tolerance_m, b.blend_tolerance_m);
    // What bounds the speed at b's start: a dwell stops, the rest is not known here.
    next_start_speed_m_s_ = a.kind == SegmentKind::dwell || b.kind == SegmentKind::dwell
                                ? 0.0
                                : std::numeric_limits<double>::infinity();
    if (blendable && (out - in).norm() > corner_chord_) {  // |out − in| = 2·sin(φ/2)
      fillet = corner_fillet(a.end_m, in, out, tolerance, max_trim);
      // A fillet bounded by the tolerance (a corner of the drawing) is chosen by its time; one bounded
      // by half a line (a vertex of chord-flattened curve, whose neighbours' fillets it meets) keeps
      // all its room: there the local model does not see the curvature steps between the fillets.
      if (fillet && model_ && fillet->trim_m < max_trim * (1 - 1e-9)) {
        fillet = chosen_fillet(*fillet, b, in, out, tolerance, max_trim);
      }
    }
    // Where the fillet is bounded by half the shorter line and would leave more of the first line
    // than an absorbing arc takes: a biarc that takes all the corner before left of the first line
    // and half of the second.
    std::optional<std::array<PathSegment, 2>> pair;
    if (fillet && held_blended_ && a.length_m <= 0.75 * held_length_m_ && fillet->trim_m >= max_trim * (1 - 1e-9) &&
        a.length_m - fillet->trim_m > absorbed_line_m(tolerance)) {
      pair = corner_biarc(a.end_m, in, out, a.length_m, 0.5 * b.length_m, tolerance);
    }
    // What is left of the first line: kept, or (shorter than shortest_segment_m, as it is when the
    // biarc takes all of it) taken into the first arc, which then starts exactly where the line did.
    const bool keep_rest = pair && ((*pair)[0].start_m - a.start_m).norm() >= shortest_segment_m;
    if (pair && !keep_rest) {
      if (const std::optional<PathSegment> first = arc_from_tangent(a.start_m, in, (*pair)[0].end_m)) {
        (*pair)[0] = *first;
      } else {
        pair.reset();
      }
    }
    if (pair) {
      const Vec2 entry = (*pair)[0].start_m;
      a.end_m = entry;
      a.length_m = (a.end_m - a.start_m).norm();
      if (keep_rest) ready_.push_back(a);
      for (const PathSegment& piece : *pair) ready_.push_back(blend_piece(piece, a, b));
      b.start_m = (*pair)[1].end_m;
      b.length_m = (b.end_m - b.start_m).norm();
    } else if (fillet) {
      a.end_m = fillet->entry_m;
      a.length_m = (a.end_m - a.start_m).norm();
      // If the two blends of a line leave (almost) nothing of it, the arc starts where the line did.
      const std::optional<PathSegment> absorbing =
          a.length_m <= absorbed_line_m(tolerance)
              ? arc_absorbing_line(a.start_m, in, *fillet, 0.25 * corner_angle_rad_)
              : std::nullopt;
      const bool keep_line = !absorbing && a.length_m >= shortest_segment_m;
      const PathSegment arc = absorbing ? *absorbing
                                        : make_arc(keep_line ? fillet->entry_m : a.start_m, fillet->exit_m,
                                                   fillet->center_m, fillet->sweep_rad);
      if (keep_line) ready_.push_back(a);
      ready_.push_back(blend_piece(arc, a, b));
      b.start_m = fillet->exit_m;
      b.length_m = (b.end_m - b.start_m).norm();
    } else {
      ready_.push_back(a);
    }
    const bool arc_ends_here = (pair || fillet) && ready_.back().kind == SegmentKind::arc;
    next_start_arc_radius_m_ = arc_ends_here ? ready_.back().radius_m : 0.0;
    next_start_arc_feed_m_s_ = arc_ends_here ? ready_.back().feed_m_s : 0.0;
    held_length_m_ = incoming->length_m;
    held_blended_ = pair || fillet;
    held_start_speed_m_s_ = next_start_speed_m_s_;
    held_start_arc_radius_m_ = next_start_arc_radius_m_;
    held_start_arc_feed_m_s_ = next_start_arc_feed_m_s_;
    held_ = b;
  }
  PathSegment out = ready_.front();
  ready_.pop_front();
  return out;
}

}  // namespace stiffpath::motion
