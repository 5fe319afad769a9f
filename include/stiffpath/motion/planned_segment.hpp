// A segment with its profile and start time, and the trajectory sample it gives at any instant.
#pragma once

#include <cstddef>
#include <optional>

#include "stiffpath/motion/junction.hpp"
#include "stiffpath/motion/path_segment.hpp"
#include "stiffpath/motion/profile.hpp"
#include "stiffpath/motion/segment_limits.hpp"

namespace stiffpath::motion {

//! A segment whose timing is final: its geometry, limits, profile and when it starts. A run of
//! tangent segments planned as one profile (see PlannerOptions::one_profile_per_run) shares that
//! profile: each of its segments covers the part of it from profile_offset_s on, for duration_s,
//! starting at arc length profile_offset_m. A segment planned alone has both offsets 0 and
//! duration_s = profile.duration_s.
struct PlannedSegment {
  PathSegment path;
  SegmentLimits limits;         //!< the limits the profile keeps (a run's: the lowest of its segments')
  Profile profile;              //!< along the path; a dwell's profile only has its cruise phase at speed 0
  double start_time_s = 0.0;    //!< from the start of the program (s)
  double duration_s = 0.0;      //!< this segment's share of the profile (s)
  double profile_offset_s = 0.0;  //!< profile time at which this segment starts (s)
  double profile_offset_m = 0.0;  //!< profile arc length at which this segment starts (m)
  double entry_speed_m_s = 0.0;   //!< path speed at the start (m/s)
  double exit_speed_m_s = 0.0;    //!< path speed at the end (m/s)
  //! Arc length along the program's whole path where this segment starts (m): the lengths of the segments
  //! before it, summed in order (set by the Sampler and by Trajectory as they take the segments).
  double path_start_m = 0.0;
  std::size_t index = 0;        //!< 0-based position in the planned program
  //! The rule that bounds the speed where its profile starts / ends, when the profile's speed there
  //! is that rule's bound (a valley of the speed); none when the speed there is set by braking or
  //! accelerating from elsewhere. SlowdownReport charges lost time to these.
  SpeedLimit entry_limit = SpeedLimit::none;
  SpeedLimit exit_limit = SpeedLimit::none;

  [[nodiscard]] double end_time_s() const noexcept { return start_time_s + duration_s; }
};

//! The state of the planned path at one instant, robot frame, SI.
struct TrajectorySample {
  double t_s = 0.0;                       //!< time from the start of the program (s)
  Vec2 position_m = Vec2::Zero();         //!< (m)
  Vec2 velocity_m_s = Vec2::Zero();       //!< (m/s)
  Vec2 acceleration_m_s2 = Vec2::Zero();  //!< analytic, centripetal part included (m/s²)
  Vec2 jerk_m_s3 = Vec2::Zero();          //!< analytic (m/s³)
  double path_speed_m_s = 0.0;            //!< speed along the path (m/s), ≥ 0
  double path_m = 0.0;                    //!< arc length along the program's path (m): path_start_m + s
  double path_acceleration_m_s2 = 0.0;    //!< tangential acceleration: the profile's d²s/dt² (m/s²)
  double path_jerk_m_s3 = 0.0;            //!< the profile's d³s/dt³ (m/s³)
  double power = 0.0;                     //!< laser power, fraction of full power 0..1 (0 when off; M4 scaled by speed)
  int line = 0;                           //!< source G-code line of the segment
  std::size_t segment = 0;                //!< index of the planned segment
  bool laser_on = false;                  //!< laser firing
};

//! The sample of a planned segment at time t_s (program time; clamped to the segment: its start
//! gives exactly its first point, its end exactly its last). With
//! T the unit tangent, N its left normal and κ the signed curvature (1/m):
//!   velocity = v·T,  acceleration = a·T + v²κ·N,  jerk = (j − v³κ²)·T + 3·v·a·κ·N,
//! where s, v, a, j come from the profile (thesis §4.3, fig. 4.3: "trapezoidal acceleration profile").
TrajectorySample evaluate(const PlannedSegment& segment, double t_s) noexcept;

//! Something that hands out planned segments in time order; nullopt at the end (a Planner, or a
//! stored Trajectory's cursor).
class SegmentSource {
 public:
  virtual ~SegmentSource() = default;
  virtual std::optional<PlannedSegment> next() = 0;
};

}  // namespace stiffpath::motion
