// Runs of tangent segments that the planner gives one profile: which segment may join a run, and the run's limits.
#pragma once

#include <cstddef>

#include "stiffpath/motion/junction.hpp"
#include "stiffpath/motion/limits.hpp"
#include "stiffpath/motion/path_segment.hpp"
#include "stiffpath/motion/segment_limits.hpp"

namespace stiffpath::motion {

//! When tangent segments are planned as one profile. Documented defaults.
struct RunRules {
  //! The speed caps of a run's segments (each lowered to the speed of the junction before it) lie
  //! within this factor of each other. The run is planned with the lowest, so no segment gives up
  //! more than 3 % of its speed.
  double speed_band = 0.97;
  //! The same for their tangential acceleration and jerk limits, which arcs lower below the lines'
  //! (segment_limits.hpp). Looser: a run keeps the lowest, which only lengthens its speed changes,
  //! while a junction between two runs, at zero acceleration, costs more on short segments.
  double tangential_band = 0.5;
  //! A run closes after this many segments (it is held in memory until its profile is solved).
  std::size_t max_segments = 1024;
  //! At most this many runs share one profile when they join on release (Planner): bounds the work
  //! of checking its junctions (at most max_joined_runs² speed bounds per profile).
  std::size_t max_joined_runs = 64;
  //! A run also closes once it is this many times as long as a speed change from rest to its cap:
  //! its junction with the next run can then be passed at the cap, so closing it costs no time.
  double closing_length_factor = 4.0;
};

//! A run being built: the range of its segments' limits and its length.
struct Run {
  SegmentLimits low;    //!< the lowest speed cap, tangential acceleration and jerk: the run's limits
  SegmentLimits high;   //!< the highest of each
  double length_m = 0.0;
  std::size_t segments = 0;
  bool dwell = false;   //!< a dwell, which is always a run of its own
  double closing_length_m = 0.0;  //!< RunRules::closing_length_factor × the change from rest to low's cap
  double lowest_feed_m_s = 0.0;   //!< the lowest programmed feed of its segments (whether a cap is an arc's)
};

//! The lower, and the higher, of each limit of two sets.
SegmentLimits lower_limits(const SegmentLimits& a, const SegmentLimits& b) noexcept;
SegmentLimits higher_limits(const SegmentLimits& a, const SegmentLimits& b) noexcept;

//! Whether segments whose lowest limits are `low` and highest `high` may share a profile (planned
//! with `low`): the speed caps within RunRules::speed_band, the tangential limits within
//! RunRules::tangential_band.
bool within_run_bands(const SegmentLimits& low, const SegmentLimits& high, const RunRules& rules) noexcept;

//! A run of one segment.
Run start_run(const PathSegment& segment, const SegmentLimits& limits, const RunRules& rules = {}) noexcept;

//! Adds `next` to `run`, whose last segment is `last`, and returns true when it may share the run's
//! profile: no dwell on either side, the run not closed (RunRules), a tangent junction
//! (tangent_junction_speed_limit > 0 with the run's tangential acceleration), and next's cap
//! (lowered to that junction's speed) and tangential limits within the band of the run's.
//! Otherwise leaves `run` as it was.
bool extend_run(Run& run, const PathSegment& last, const SegmentLimits& last_limits, const PathSegment& next,
                const SegmentLimits& next_limits, const MotionLimits& limits, const JunctionRules& junction,
                const RunRules& rules) noexcept;

}  // namespace stiffpath::motion
