// PathTiming: the reference filters on the arc length along the planned path, restarted at every stop.
#pragma once

#include <cstdint>
#include <deque>

#include "stiffpath/compensation/reference_filter.hpp"
#include "stiffpath/motion/sampler.hpp"

namespace stiffpath::job::detail {

using compensation::Vec2;

//! Filters only the timing of a planned path: the chain filters the arc length s(t) of the planned samples, and
//! each output is the planned path's own point at the filtered s̄, its rates from the chain rule on the path's
//! line or arc (compensation::motion_along). So no point leaves the planned path (to rounding), and a laser or
//! power switch stays where the path switches, at the instant s̄ passes it. At every stop of the plan (an exact
//! stop, a dwell's ends) and every corner it passes at speed, the input rests for the chain's delay and a sample
//! before the next move, so that no output mixes two moves: each move is filtered on its own and stops where the
//! plan stops or turns (a corner is never cut, nor passed with a velocity step), at the cost of that rest per stop.
//! The source must keep its segments (SampleSource::keep_segments).
class PathTiming {
 public:
  //! `history` is `source`'s, kept for at least the chain's delay and three samples more.
  PathTiming(motion::SampleSource& source, const motion::SegmentHistory& history, compensation::FilterChain& filters,
             double rate_hz);
  //! The next filtered sample; false after the last one.
  bool next(compensation::TaskSample& out);

 private:
  // One input of the chain, pushed `repeat` times (an inserted rest), with the arc length its move starts at.
  struct Pending {
    compensation::FilterSample sample;
    compensation::PlannedPoint point;
    double move_start_m = 0.0;
    std::int64_t repeat = 1;
  };
  void take(const motion::TrajectorySample& planned);  // queues the planned sample and the rests before it
  void start_rest(double s_m, const compensation::FilterSample& meta, const Vec2& point_m);
  void close_rest();  // tops the current rest up to the chain's delay and starts the next move there
  // True where the filters restart between two segments: a stop of the plan, or a corner it passes at speed.
  [[nodiscard]] bool restarts(const motion::PlannedSegment* before, const motion::PlannedSegment& after) const noexcept;
  [[nodiscard]] const motion::PlannedSegment* segment(std::size_t index) const noexcept;
  const motion::PlannedSegment& segment_at(double s_m) noexcept;  // the line or arc through arc length s_m
  [[nodiscard]] compensation::TaskSample on_path(const compensation::FilterSample& filtered, double low_m,
                                                 double high_m);

  motion::SampleSource& source_;
  const motion::SegmentHistory& history_;
  compensation::FilterChain& filters_;
  double rate_hz_;
  double corner_angle_rad_;  // a turn beyond this is a corner (motion::JunctionRules's)
  std::int64_t delay_ = 0;  // how long every stop rests: the chain's delay and one sample
  std::deque<Pending> queue_;
  std::int64_t pushed_ = 0;     // inputs given to the chain (its time base)
  bool started_ = false, source_done_ = false;
  std::size_t last_segment_ = 0;  // segment of the last planned sample
  // The rest the input is in (resting_), and the move before it.
  bool resting_ = true;
  double rest_m_ = 0.0;
  std::int64_t rest_samples_ = 0;
  compensation::FilterSample rest_meta_;  // laser, power and line while resting
  bool rest_fires_ = false;               // the rest holds a dwell with the laser on …
  compensation::FilterSample fire_meta_;  // … whose laser, power and line these are
  Vec2 rest_point_m_ = Vec2::Zero();
  double move_start_m_ = 0.0;
  // The clamp of the latest output's arc length (the move it belongs to), and the segment it was found on.
  double low_m_ = 0.0, high_m_ = 0.0;
  std::size_t cursor_ = 0;
};

}  // namespace stiffpath::job::detail
