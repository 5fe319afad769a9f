// Runs of tangent segments planned as one profile: the joining rule (tangency, junction steps, a band of limits).
#include "stiffpath/motion/planner_run.hpp"

#include <algorithm>

#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {

namespace {

double closing_length(const SegmentLimits& low, const RunRules& rules) noexcept {
  if (!(low.max_velocity_m_s > 0.0)) return 0.0;
  return rules.closing_length_factor *
         speed_change(0.0, low.max_velocity_m_s, low.max_acceleration_m_s2, low.max_jerk_m_s3).distance_m;
}

}  // namespace

SegmentLimits lower_limits(const SegmentLimits& a, const SegmentLimits& b) noexcept {
  return {std::min(a.max_velocity_m_s, b.max_velocity_m_s), std::min(a.max_acceleration_m_s2, b.max_acceleration_m_s2),
          std::min(a.max_jerk_m_s3, b.max_jerk_m_s3)};
}

SegmentLimits higher_limits(const SegmentLimits& a, const SegmentLimits& b) noexcept {
  return {std::max(a.max_velocity_m_s, b.max_velocity_m_s), std::max(a.max_acceleration_m_s2, b.max_acceleration_m_s2),
          std::max(a.max_jerk_m_s3, b.max_jerk_m_s3)};
}

bool within_run_bands(const SegmentLimits& low, const SegmentLimits& high, const RunRules& rules) noexcept {
  return low.max_velocity_m_s >= rules.speed_band * high.max_velocity_m_s &&
         low.max_acceleration_m_s2 >= rules.tangential_band * high.max_acceleration_m_s2 &&
         low.max_jerk_m_s3 >= rules.tangential_band * high.max_jerk_m_s3;
}

Run start_run(const PathSegment& segment, const SegmentLimits& limits, const RunRules& rules) noexcept {
  return Run{limits, limits, segment.length_m, 1, segment.kind == SegmentKind::dwell, closing_length(limits, rules),
             segment.feed_m_s};
}

bool extend_run(Run& run, const PathSegment& last, const SegmentLimits& last_limits, const PathSegment& next,
                const SegmentLimits& next_limits, const MotionLimits& limits, const JunctionRules& junction,
                const RunRules& rules) noexcept {
  if (run.dwell || last.kind == SegmentKind::dwell || next.kind == SegmentKind::dwell) return false;
  if (run.segments >= rules.max_segments) return false;
  if (run.length_m >= run.closing_length_m) return false;

  const double acceleration = std::min(run.low.max_acceleration_m_s2, next_limits.max_acceleration_m_s2);
  const double junction_speed =
      tangent_junction_speed_limit(last, last_limits, next, next_limits, limits, junction, acceleration);
  if (!(junction_speed > 0.0)) return false;
  const SegmentLimits joining{std::min(next_limits.max_velocity_m_s, junction_speed), next_limits.max_acceleration_m_s2,
                              next_limits.max_jerk_m_s3};
  const SegmentLimits low = lower_limits(run.low, joining), high = higher_limits(run.high, joining);
  if (!within_run_bands(low, high, rules)) return false;
  if (low.max_velocity_m_s != run.low.max_velocity_m_s || low.max_acceleration_m_s2 != run.low.max_acceleration_m_s2 ||
      low.max_jerk_m_s3 != run.low.max_jerk_m_s3) {
    run.closing_length_m = closing_length(low, rules);
  }
  run.low = low;
  run.high = high;
  run.lowest_feed_m_s = std::min(run.lowest_feed_m_s, next.feed_m_s);
  run.length_m += next.length_m;
  ++run.segments;
  return true;
}

}  // namespace stiffpath::motion
