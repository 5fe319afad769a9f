// Look-ahead planner: junction speeds, backward and forward passes, and one profile per segment, streamed.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>

#include "stiffpath/motion/junction.hpp"
#include "stiffpath/motion/limits.hpp"
#include "stiffpath/motion/path_source.hpp"
#include "stiffpath/motion/planned_segment.hpp"

namespace stiffpath::motion {

//! Planner settings. Documented defaults.
struct PlannerOptions {
  JunctionRules junction;  //!< corner angle and junction time τ
  //! Upper bound on the look-ahead window (segments); 0 = unbounded, i.e. whole-program look-ahead.
  //! With a bound, a full window releases its oldest segment with the speeds known so far: still
  //! within every limit and reachable, but possibly slower than the whole-program plan. Without a
  //! bound the window still only holds the segments since the last junction whose speed can no
  //! longer change (see docs/motion.md), which for real programs is a few hundred at most.
  std::size_t max_lookahead_segments = 0;
};

//! Counters of a planning run.
struct PlannerStatistics {
  std::size_t segments = 0;          //!< planned segments handed out
  std::size_t peak_window = 0;       //!< largest number of segments held at once
  std::size_t forced_releases = 0;   //!< segments released early because the window was full
  //! Entry speeds evaluated by the backward passes (each one reachable_speed). Passes are batched
  //! so that this stays at most 2·(segments + peak_window + 1) however long the braking distances
  //! are; on CAM programs, whose windows are short, it is 2 per segment.
  std::size_t entry_evaluations = 0;
};

//! Plans the segments of a PathSource with look-ahead over the whole program and hands them out
//! one at a time with their final profiles. Each junction gets the highest speed that (1) its
//! junction rules allow, (2) the rest of the program can still brake from (backward pass, with
//! every segment starting and ending at zero tangential acceleration), and (3) can be reached from
//! the start (forward pass). A segment is released as soon as a later junction is pinned, i.e. its
//! speed is set by its own rules rather than by what follows: from then on nothing later in the
//! program can change it, so the streamed result equals planning the whole program at once.
//! The program starts and ends at rest. A profile that cannot be built is an internal error
//! (std::logic_error); invalid limits throw stiffpath::Error.
class Planner final : public SegmentSource {
 public:
  Planner(PathSource& source, const MotionLimits& limits, const PlannerOptions& options = {});
  std::optional<PlannedSegment> next() override;
  [[nodiscard]] const PlannerStatistics& statistics() const noexcept { return statistics_; }

 private:
  struct Node {
    PathSegment path;
    SegmentLimits limits;
    double entry_limit_m_s = 0.0;  // junction rules at the start
    double entry_max_m_s = 0.0;    // after the backward pass over the window
    double reach_from_rest_m_s = 0.0;  // reachable_speed(length, 0): the exit-independent part of the entry bound
  };
  void push(const PathSegment& segment);
  void backward_pass();
  [[nodiscard]] double exit_max(std::size_t i) const noexcept;
  [[nodiscard]] double entry_bound(const Node& node, double exit_max_m_s) const noexcept;
  PlannedSegment release();

  PathSource& source_;
  MotionLimits limits_;
  PlannerOptions options_;
  std::deque<Node> window_;
  std::size_t front_index_ = 0;   // program index of window_.front()
  std::size_t pinned_end_ = 0;    // 1 + program index of the last pinned junction's segment (0: none)
  double entry_speed_m_s_ = 0.0;  // committed speed at the start of window_.front()
  double clock_s_ = 0.0;
  std::size_t pending_ = 0;       // segments pushed since the last backward pass (at the window's end)
  std::size_t pass_depth_ = 0;    // earlier segments the last backward pass changed
  bool exhausted_ = false;
  PlannerStatistics statistics_;
};

}  // namespace stiffpath::motion
