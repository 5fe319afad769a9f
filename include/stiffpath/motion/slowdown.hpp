// Where a planned job loses time against its programmed feeds, and which limit made it: totals and the slowest stretches.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "stiffpath/motion/junction.hpp"
#include "stiffpath/motion/limits.hpp"
#include "stiffpath/motion/path_source.hpp"
#include "stiffpath/motion/planned_segment.hpp"

namespace stiffpath::motion {

//! Number of SpeedLimit kinds (the size of a per-limit table).
inline constexpr std::size_t speed_limit_kinds = 8;

//! One stretch of the job where the path runs below its programmed feed: consecutive slowed
//! segments of one kind (marking, feed moves without the laser, or rapids), from the first source
//! line to the last, and the time each limit cost in it.
struct SlowStretch {
  int first_line = 0, last_line = 0;  //!< lowest and highest source line of its segments
  double start_s = 0.0;               //!< when it begins (s)
  double duration_s = 0.0;            //!< planned time (s)
  double programmed_s = 0.0;          //!< time of its planned path at the programmed feeds (s)
  double lowest_speed_m_s = 0.0;      //!< lowest speed at a junction in it (m/s)
  std::array<double, speed_limit_kinds> lost_s{};  //!< time lost to each SpeedLimit (s)

  [[nodiscard]] double lost_total_s() const noexcept;
};

//! The time of a program at its programmed feeds: each move as the program gives it (before merging
//! and blending) at min(F, v_max), G0 at v_max, dwells as programmed. A path stage that passes the
//! reader's segments on unchanged.
class FeedClock final : public PathSource {
 public:
  FeedClock(PathSource& source, const MotionLimits& limits) : source_(source), limits_(limits) {}
  std::optional<PathSegment> next() override;
  [[nodiscard]] double programmed_s() const noexcept { return programmed_s_; }

 private:
  PathSource& source_;
  MotionLimits limits_;
  double programmed_s_ = 0.0;
};

//! The account of a planned job's time: at the programmed feeds (FeedClock) against the plan, the
//! difference split by the limit that caused it, and the slowest stretches (by time lost). Blends and
//! merged lines shorten the path; the time that saves at the feeds is shortcut_s(), so that
//! planned = programmed + Σ lost − shortcut. A segment's loss has three parts:
//! - its own speed cap below the target (an arc's centripetal share of a and j): arc_speed;
//! - its profile's cap below its own (the run's tangent junctions: v²·Δκ ≤ j·τ): curvature_step;
//! - its profile's speed changes: the part before the profile's peak goes to the valley it climbs
//!   from (the junction rule that bound its entry, or the one before), the part after to the valley
//!   it descends into (the next junction whose rule binds the speed, known once it is reached).
//! Feeds above the speed limit are counted apart (feed_above_limit_s), not as a loss. Joint limits
//! never slow a plan: it keeps Cartesian limits, and plan and run refuse points beyond the joints'.
//! Streaming: O(1) work per segment, memory for max_stretches stretches.
class SlowdownReport {
 public:
  explicit SlowdownReport(const MotionLimits& limits, std::size_t max_stretches = 5);
  //! The next planned segment, in time order.
  void add(const PlannedSegment& segment);
  //! The program has ended (at rest): what was still descending goes to its end. `programmed_s`: the
  //! program's time at its feeds (FeedClock).
  void finish(double programmed_s);

  [[nodiscard]] double planned_s() const noexcept { return planned_s_; }
  //! Time at the programmed feeds (s), as the program gives its moves.
  [[nodiscard]] double programmed_s() const noexcept { return programmed_s_; }
  //! The time the planned path's moves would take at their feeds, less programmed_s(): what blends
  //! and merges save by shortening the path (s, ≥ 0 up to rounding).
  [[nodiscard]] double shortcut_s() const noexcept { return programmed_s_ - at_feed_s_; }
  //! Time the feeds above max_velocity would have saved (s): the machine's limit, not a loss.
  [[nodiscard]] double feed_above_limit_s() const noexcept { return feed_above_limit_s_; }
  [[nodiscard]] const std::array<double, speed_limit_kinds>& lost_s() const noexcept { return lost_s_; }
  //! The slowest stretches, most time lost first (complete after finish()).
  [[nodiscard]] std::vector<SlowStretch> slowest() const;

 private:
  void charge(SpeedLimit limit, double seconds);
  void close_stretch();
  void valley(SpeedLimit limit);

  MotionLimits limits_;
  std::size_t max_stretches_;
  double planned_s_ = 0.0, programmed_s_ = 0.0, at_feed_s_ = 0.0, feed_above_limit_s_ = 0.0;
  std::array<double, speed_limit_kinds> lost_s_{};
  double pending_s_ = 0.0;                 // descending loss waiting for its valley
  SpeedLimit climbing_ = SpeedLimit::rest;  // the valley the path climbs from
  std::optional<SlowStretch> open_;
  int last_kind_ = -1;                     // 0 feed move, 1 laser on, 2 rapid: a stretch holds one kind
  std::vector<SlowStretch> stretches_;     // at most max_stretches_, any order
  bool finished_ = false;
};

//! Passes planned segments on unchanged and accounts for them in a SlowdownReport; `clock` (the
//! FeedClock behind the reader of the same plan) gives the programmed time at the end.
class SlowdownTap final : public SegmentSource {
 public:
  SlowdownTap(SegmentSource& source, const FeedClock& clock, const MotionLimits& limits)
      : source_(source), clock_(clock), report_(limits) {}
  std::optional<PlannedSegment> next() override;
  [[nodiscard]] const SlowdownReport& report() const noexcept { return report_; }

 private:
  SegmentSource& source_;
  const FeedClock& clock_;
  SlowdownReport report_;
};

}  // namespace stiffpath::motion
