// Evaluation of a planned segment: profile state along the path combined with the path's tangent and curvature.
#include "stiffpath/motion/planned_segment.hpp"

#include <algorithm>

namespace stiffpath::motion {

TrajectorySample evaluate(const PlannedSegment& segment, double t_s) noexcept {
  // At or past the end time the end state exactly ((start + d) − start need not equal d).
  const bool at_end = t_s >= segment.end_time_s();
  const double local = at_end ? segment.duration_s : std::clamp(t_s - segment.start_time_s, 0.0, segment.duration_s);
  const ProfileState state = segment.profile.state_at(segment.profile_offset_s + local);
  const double s_m = at_end ? segment.path.length_m
                     : local > 0.0 ? std::clamp(state.s_m - segment.profile_offset_m, 0.0, segment.path.length_m)
                                   : 0.0;
  const PathPoint point = point_at(segment.path, s_m);
  const Vec2& tangent = point.tangent;
  const Vec2 normal = left_normal(tangent);
  const double k = point.curvature_1_m, v = state.v_m_s, a = state.a_m_s2, j = state.j_m_s3;

  TrajectorySample sample;
  sample.t_s = t_s;
  sample.position_m = point.position_m;
  sample.velocity_m_s = v * tangent;
  sample.acceleration_m_s2 = a * tangent + (v * v * k) * normal;
  sample.jerk_m_s3 = (j - v * v * v * k * k) * tangent + (3.0 * v * a * k) * normal;
  sample.path_speed_m_s = v;
  sample.path_m = segment.path_start_m + s_m;
  sample.path_acceleration_m_s2 = a;
  sample.path_jerk_m_s3 = j;
  sample.power = power_at(segment.path, v);
  sample.line = segment.path.line;
  sample.segment = segment.index;
  sample.laser_on = segment.path.laser_on;
  return sample;
}

}  // namespace stiffpath::motion
