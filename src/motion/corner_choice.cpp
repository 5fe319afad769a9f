// Choosing a G64 corner's fillet (or none) by the time the lines around it take, against the corner without it.
#include "stiffpath/motion/corner_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stiffpath/motion/path_segment.hpp"
#include "stiffpath/motion/profile.hpp"
#include "stiffpath/motion/segment_limits.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {

namespace {

constexpr int trims_tried = 11;  // d_max · 2^-k, k = 0 … 10
constexpr double infinity = std::numeric_limits<double>::infinity();

// The fastest way over `length` from at most `start_bound` (capped by `cap`) to exactly `w` at its end.
// +inf when w cannot be reached.
double time_in(double length, double start_bound, double w, double cap, const MotionLimits& l) noexcept {
  const double a = l.max_acceleration_m_s2, j = l.max_jerk_m_s3;
  const double start = std::min({start_bound, cap, reachable_speed(length, w, a, j)});
  Profile p;
  if (solve_profile({length, start, w, cap, a, j}, p) != ProfileStatus::ok) return infinity;
  return p.duration_s;
}

// The fastest way over `length` from `w` with a free end: speed up towards `cap`, then cruise.
double time_out(double length, double w, double cap, const MotionLimits& l) noexcept {
  const double a = l.max_acceleration_m_s2, j = l.max_jerk_m_s3;
  const double end = std::min(cap, reachable_speed(length, w, a, j));
  const SpeedChange c = speed_change(w, end, a, j);
  return c.duration_s + (end >= cap ? std::max(length - c.distance_m, 0.0) / cap : 0.0);
}

struct Option {
  double time_s = infinity;
  double pass_speed_m_s = 0.0;
};

// The lines around the corner with a fillet of trim d.
Option with_fillet(const CornerInput& c, double trim, const CornerSpeedModel& model) noexcept {
  const MotionLimits& l = model.limits;
  const double radius = trim / std::tan(0.5 * c.turn_rad), length = radius * c.turn_rad;
  PathSegment arc = make_arc(Vec2(radius, 0.0), Vec2(radius * std::cos(c.turn_rad), radius * std::sin(c.turn_rad)),
                             Vec2::Zero(), c.turn_rad);
  arc.feed_m_s = c.feed_m_s;
  const SegmentLimits own = segment_limits(arc, l);  // the arc's limits, as the planner gives them
  const double in = c.in_length_m - trim, out = c.out_length_m - trim;
  const double start = std::min(c.in_start_speed_m_s, c.in_cap_m_s);
  const double reach = reachable_speed(in, std::isfinite(start) ? start : 0.0, l.max_acceleration_m_s2, l.max_jerk_m_s3);
  const double w = std::min({c.in_cap_m_s, c.out_cap_m_s, own.max_velocity_m_s,
                             std::sqrt(l.max_jerk_m_s3 * model.junction_time_s * radius),
                             std::isfinite(start) ? reach : infinity});
  Option o;
  o.pass_speed_m_s = w;
  if (!(w > 0.0)) return o;
  double arc_s = length / w;
  Profile p;
  if (solve_profile({length, w, w, own.max_velocity_m_s, own.max_acceleration_m_s2, own.max_jerk_m_s3}, p) ==
      ProfileStatus::ok) {
    arc_s = std::min(arc_s, p.duration_s);
  }
  o.time_s = time_in(in, c.in_start_speed_m_s, w, c.in_cap_m_s, l) + arc_s + time_out(out, w, c.out_cap_m_s, l);
  return o;
}

}  // namespace

CornerChoice choose_corner(const CornerInput& c, const CornerSpeedModel& model) noexcept {
  CornerChoice choice;
  choice.trim_m = c.max_trim_m;
  if (!(c.max_trim_m > 0.0) || !(c.turn_rad > 0.0) || !(c.in_cap_m_s > 0.0) || !(c.out_cap_m_s > 0.0)) return choice;
  const Option full = with_fillet(c, c.max_trim_m, model);
  choice.pass_speed_m_s = full.pass_speed_m_s;
  choice.time_s = full.time_s;
  if (full.pass_speed_m_s >= std::min(c.in_cap_m_s, c.out_cap_m_s)) return choice;  // no slowing down at all
  // Without a fillet the corner is passed at the speed whose velocity step 2·v·sin(φ/2) is j·τ² (junction.hpp).
  const MotionLimits& l = model.limits;
  const double tau = model.junction_time_s;
  const double unrounded = std::min({c.in_cap_m_s, c.out_cap_m_s, l.max_jerk_m_s3 * tau * tau / (2.0 * std::sin(0.5 * c.turn_rad))});
  choice.unrounded_time_s =
      time_in(c.in_length_m, c.in_start_speed_m_s, unrounded, c.in_cap_m_s, l) + time_out(c.out_length_m, unrounded, c.out_cap_m_s, l);
  double trim = c.max_trim_m, previous = full.time_s;
  for (int k = 1; k < trims_tried; ++k) {
    trim *= 0.5;
    const Option o = with_fillet(c, trim, model);
    if (o.time_s < choice.time_s) {
      choice.trim_m = trim;
      choice.pass_speed_m_s = o.pass_speed_m_s;
      choice.time_s = o.time_s;
    }
    if (k >= 2 && !(o.time_s < previous)) break;  // past the best: smaller fillets only take longer
    previous = o.time_s;
  }
  if (!(choice.time_s <= choice.unrounded_time_s)) {
    choice.trim_m = 0.0;
    choice.pass_speed_m_s = unrounded;
    choice.time_s = choice.unrounded_time_s;
  }
  return choice;
}

}  // namespace stiffpath::motion
