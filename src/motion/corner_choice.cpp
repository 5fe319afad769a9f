// Choosing a G64 corner's fillet (or none) by the time it costs against the stop it replaces.
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

// Time lost against cruising at `cruise` while changing speed between `cruise` and `w`: T − D/cruise.
double change_loss(double cruise, double w, const MotionLimits& limits) noexcept {
  if (!(cruise > 0.0) || w >= cruise) return 0.0;
  const SpeedChange c = speed_change(cruise, w, limits.max_acceleration_m_s2, limits.max_jerk_m_s3);
  return c.duration_s - c.distance_m / cruise;
}

struct Blend {
  double loss_s = std::numeric_limits<double>::infinity();
  double pass_speed_m_s = 0.0;
};

Blend blend_loss(const CornerInput& c, double trim, const CornerSpeedModel& model) noexcept {
  const double half = 0.5 * c.turn_rad;
  const double radius = trim / std::tan(half), length = radius * c.turn_rad;
  // The arc's own limits, as the planner gives them (a arc of this radius at the feed).
  PathSegment arc = make_arc(Vec2(radius, 0.0), Vec2(radius * std::cos(c.turn_rad), radius * std::sin(c.turn_rad)),
                             Vec2::Zero(), c.turn_rad);
  arc.feed_m_s = c.feed_m_s;
  const SegmentLimits own = segment_limits(arc, model.limits);
  const double junction = std::sqrt(model.limits.max_jerk_m_s3 * model.junction_time_s * radius);
  const double w = std::min({c.in_speed_m_s, c.out_speed_m_s, own.max_velocity_m_s, junction});
  Blend b;
  b.pass_speed_m_s = w;
  if (!(w > 0.0)) return b;
  double arc_s = length / w;
  Profile profile;
  if (solve_profile({length, w, w, own.max_velocity_m_s, own.max_acceleration_m_s2, own.max_jerk_m_s3}, profile) ==
      ProfileStatus::ok) {
    arc_s = std::min(arc_s, profile.duration_s);
  }
  b.loss_s = change_loss(c.in_speed_m_s, w, model.limits) + change_loss(c.out_speed_m_s, w, model.limits) + arc_s -
             trim / c.in_speed_m_s - trim / c.out_speed_m_s;
  return b;
}

}  // namespace

CornerChoice choose_corner(const CornerInput& c, const CornerSpeedModel& model) noexcept {
  CornerChoice choice;
  if (!(c.max_trim_m > 0.0) || !(c.turn_rad > 0.0) || !(c.in_speed_m_s > 0.0) || !(c.out_speed_m_s > 0.0)) {
    choice.trim_m = c.max_trim_m;
    return choice;
  }
  const Blend full = blend_loss(c, c.max_trim_m, model);
  choice.trim_m = c.max_trim_m;
  choice.pass_speed_m_s = full.pass_speed_m_s;
  choice.loss_s = full.loss_s;
  if (full.pass_speed_m_s >= std::min(c.in_speed_m_s, c.out_speed_m_s)) return choice;  // no slowing down at all
  // Without a fillet the corner is passed at the speed whose velocity step 2·v·sin(φ/2) is j·τ² (junction.hpp).
  const double tau = model.junction_time_s;
  const double unrounded = std::min({c.in_speed_m_s, c.out_speed_m_s,
                                     model.limits.max_jerk_m_s3 * tau * tau / (2.0 * std::sin(0.5 * c.turn_rad))});
  choice.stop_loss_s = change_loss(c.in_speed_m_s, unrounded, model.limits) + change_loss(c.out_speed_m_s, unrounded, model.limits);
  double trim = c.max_trim_m;
  for (int k = 1; k < trims_tried; ++k) {
    trim *= 0.5;
    const Blend b = blend_loss(c, trim, model);
    if (b.loss_s < choice.loss_s) {
      choice.trim_m = trim;
      choice.pass_speed_m_s = b.pass_speed_m_s;
      choice.loss_s = b.loss_s;
    }
  }
  if (!(choice.loss_s <= choice.stop_loss_s)) {
    choice.trim_m = 0.0;
    choice.pass_speed_m_s = unrounded;
    choice.loss_s = choice.stop_loss_s;
  }
  return choice;
}

}  // namespace stiffpath::motion
