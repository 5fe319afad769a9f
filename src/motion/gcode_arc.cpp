// G2/G3 arcs from I/J (centre relative to the start) or R (radius; negative for more than 180°).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "gcode_interpreter.hpp"

namespace stiffpath::motion {

namespace {

constexpr double same_point_m = 1e-9;  // closer end points make a full circle

// Signed sweep from start to end about the centre: (0, 2π] counter-clockwise, [−2π, 0) clockwise.
double sweep_between(const Vec2& start, const Vec2& end, const Vec2& center, bool clockwise) {
  const Vec2 a = start - center, b = end - center;
  double sweep = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));  // (−π, π]
  if (clockwise && sweep >= 0.0) sweep -= 2.0 * std::numbers::pi;
  if (!clockwise && sweep <= 0.0) sweep += 2.0 * std::numbers::pi;
  return sweep;
}

std::string mm(double m) { return fmt::format("{:.4f} mm", m * 1e3); }

// The largest |x| or |y| the arc reaches: its end points and the axis crossings inside its sweep.
double reach_m(const PathSegment& arc) {
  double reach = std::max(arc.start_m.cwiseAbs().maxCoeff(), arc.end_m.cwiseAbs().maxCoeff());
  const double two_pi = 2.0 * std::numbers::pi;
  for (int quarter = 0; quarter < 4; ++quarter) {
    const double angle = quarter * 0.5 * std::numbers::pi;
    const double ahead = arc.sweep_rad >= 0.0 ? angle - arc.start_angle_rad : arc.start_angle_rad - angle;
    if (std::fmod(std::fmod(ahead, two_pi) + two_pi, two_pi) > std::abs(arc.sweep_rad)) continue;
    const Vec2 point = arc.center_m + arc.radius_m * Vec2(std::cos(angle), std::sin(angle));
    reach = std::max(reach, point.cwiseAbs().maxCoeff());
  }
  return reach;
}

// The arc, refused at its motion word if it is larger than the reader accepts.
PathSegment checked(const detail::GcodeBlock& b, const GcodeWord& motion, PathSegment arc) {
  if (arc.radius_m > max_arc_radius_m) {
    b.fail(motion, fmt::format("radius {:g} mm is beyond {:.0f} mm, the largest accepted", arc.radius_m * 1e3,
                               max_arc_radius_m * 1e3));
  }
  if (reach_m(arc) > max_coordinate_m) {
    b.fail(motion, fmt::format("the arc reaches beyond ±{:g} mm in the robot frame, the largest accepted",
                               max_coordinate_m * 1e3));
  }
  return arc;
}

}  // namespace

PathSegment build_arc(const detail::GcodeBlock& b, const GcodeWord& motion, bool clockwise, const Vec2& start,
                      const Vec2& end, double scale_m, double tolerance_m) {
  for (const GcodeWord* word : {b.i, b.j, b.r}) {
    if (word != nullptr && std::abs(word->value * scale_m) > max_arc_radius_m) {
      b.fail(*word, fmt::format("beyond ±{:.0f} mm, the largest accepted for I, J and R", max_arc_radius_m * 1e3));
    }
  }
  const bool full_circle = (end - start).norm() < same_point_m;
  if (b.r != nullptr) {
    if (b.i != nullptr || b.j != nullptr) b.fail(*b.r, "give the arc's centre (I, J) or its radius (R), not both");
    if (full_circle) b.fail(*b.r, "a full circle needs its centre (I, J); R cannot place it");
    const double radius = std::abs(b.r->value) * scale_m;
    if (radius <= 0.0) b.fail(*b.r, "radius must not be zero");
    const Vec2 chord = end - start;
    const double half = 0.5 * chord.norm();
    double h2 = radius * radius - half * half;
    if (h2 < 0.0) {
      if (half - radius > std::max(tolerance_m, 1e-3 * radius)) {
        b.fail(*b.r, "radius " + mm(radius) + " is less than half the distance to the end point (" + mm(half) + ")");
      }
      h2 = 0.0;
    }
    // Short arc (R > 0): the centre lies left of the chord for G3, right for G2; R < 0 swaps.
    const bool left = (!clockwise) == (b.r->value > 0.0);
    const Vec2 normal = left_normal(chord / chord.norm());
    const Vec2 center = 0.5 * (start + end) + (left ? 1.0 : -1.0) * std::sqrt(h2) * normal;
    return checked(b, motion, make_arc(start, end, center, sweep_between(start, end, center, clockwise)));
  }
  if (b.i == nullptr && b.j == nullptr) {
    b.fail(motion, "an arc needs its centre (I, J) or its radius (R)");
  }
  const Vec2 offset((b.i != nullptr ? b.i->value : 0.0) * scale_m, (b.j != nullptr ? b.j->value : 0.0) * scale_m);
  Vec2 center = start + offset;
  const double r_start = offset.norm();
  const GcodeWord& centre_word = b.i != nullptr ? *b.i : *b.j;
  if (r_start < same_point_m) b.fail(centre_word, "the arc's centre coincides with its start point");
  if (full_circle) {
    return checked(b, motion, make_arc(start, start, center, clockwise ? -2.0 * std::numbers::pi : 2.0 * std::numbers::pi));
  }
  const double r_end = (end - center).norm();
  if (std::abs(r_end - r_start) > std::max(tolerance_m, 1e-3 * r_start)) {
    b.fail(motion, "the end point is not on the arc: radius " + mm(r_start) + " at the start, " + mm(r_end) +
                       " at the end");
  }
  // Within the tolerance, move the centre onto the chord's perpendicular bisector so that the arc
  // ends exactly at the programmed point.
  const Vec2 mid = 0.5 * (start + end);
  const Vec2 normal = left_normal((end - start).normalized());
  center = mid + (center - mid).dot(normal) * normal;
  return checked(b, motion, make_arc(start, end, center, sweep_between(start, end, center, clockwise)));
}

}  // namespace stiffpath::motion
