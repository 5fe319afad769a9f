// Look-ahead planner: junction speeds, backward and forward passes, and one profile per segment, streamed.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include "stiffpath/motion/junction.hpp"
#include "stiffpath/motion/limits.hpp"
#include "stiffpath/motion/path_source.hpp"
#include "stiffpath/motion/planned_segment.hpp"
#include "stiffpath/motion/planner_run.hpp"

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
  //! Plan each run of tangent segments with similar limits (RunRules) as one profile, so that the
  //! tangential acceleration carries across their junctions: chord-flattened contours then reach
  //! their feed. false: one profile per segment, starting and ending at zero acceleration.
  bool one_profile_per_run = true;
  RunRules runs;  //!< which tangent segments share a profile
  //! Once a run's entry speed is known, let the runs after it join its profile where it cannot
  //! reach the bounds of the junctions between them (Planner::plan_merge): blended contours then
  //! speed up and slow down through the curvature steps of their fillets without stopping their
  //! acceleration at each. false: each run keeps its own profile.
  bool join_runs = true;
};

//! Counters of a planning run.
struct PlannerStatistics {
  std::size_t segments = 0;          //!< planned segments handed out
  std::size_t peak_window = 0;       //!< largest number of segments held at once
  std::size_t forced_releases = 0;   //!< segments released early because the window was full
  //! Entry speeds evaluated by the backward passes (each one reachable_speed). Passes are batched
  //! so that this stays at most 4·runs + 2·(peak_window + 1) however long the braking distances
  //! are; on CAM programs it is 0.5 to 3 per segment.
  std::size_t entry_evaluations = 0;
  std::size_t runs = 0;              //!< profiles solved (a run of tangent segments has one)
  std::size_t joined_runs = 0;       //!< runs that joined the profile of the run before them on release
};

//! Plans the segments of a PathSource with look-ahead over the whole program and hands them out
//! one at a time with their final profiles. Tangent segments with similar limits are gathered into
//! runs (planner_run.hpp) that get one profile each. Each junction between runs gets the highest
//! speed that (1) its junction rules allow, (2) the rest of the program can still brake from
//! (backward pass, with every run starting and ending at zero tangential acceleration), and (3)
//! can be reached from the start (forward pass). On release, once its entry speed is known, the
//! runs after a run may join its profile where it provably stays below the bounds of the junctions
//! between them (plan_merge), so that the acceleration carries across them. A run is released as
//! soon as a later junction is pinned, i.e. its speed is set by its own rules rather than by what
//! follows (and, when the joining depends on what follows, once that is pinned too): from then on
//! nothing later in the program can change it, so the streamed result equals planning the whole
//! program at once. The program starts and ends at rest. A profile that cannot be built is an internal error
//! (std::logic_error); invalid limits throw stiffpath::Error.
class Planner final : public SegmentSource {
 public:
  Planner(PathSource& source, const MotionLimits& limits, const PlannerOptions& options = {});
  std::optional<PlannedSegment> next() override;
  [[nodiscard]] const PlannerStatistics& statistics() const noexcept { return statistics_; }

 private:
  struct Member {  // one segment of a run
    PathSegment path;
    double offset_m = 0.0;  // arc length of the run before it
  };
  struct Node {  // a closed run: one profile
    std::size_t members = 0;   // its segments, in order at the front of members_ once it is the front node
    double length_m = 0.0;
    SegmentLimits limits;      // the lowest of its segments' limits: its profile's
    SegmentLimits high;        // the highest (RunRules bands)
    bool dwell = false;
    double dwell_s = 0.0;
    int line = 0;              // source line of its first segment
    double entry_limit_m_s = 0.0;      // junction rules at the start
    SpeedLimit entry_cause = SpeedLimit::rest;  // which rule gives entry_limit_m_s
    double entry_max_m_s = 0.0;        // after the backward pass over the window
    double reach_from_rest_m_s = 0.0;  // reachable_speed(length, 0): the exit-independent part of the entry bound
  };
  struct Release {  // the run whose segments are being handed out
    Profile profile;
    SegmentLimits limits;
    std::size_t members_left = 0;
    double profile_time_s = 0.0;  // where the next segment starts on the profile
    double speed_m_s = 0.0;       // and its speed there
    double cruise_start_s = 0.0;  // the cruise phase: where it starts in time and arc length
    double cruise_start_m = 0.0;
    SpeedLimit entry_limit = SpeedLimit::none;  // the rules binding its ends' speeds (PlannedSegment)
    SpeedLimit exit_limit = SpeedLimit::none;
  };
  void add(const PathSegment& segment);
  void close_run();
  void backward_pass();
  struct Merge {  // the runs that join the front run's profile (plan_merge)
    std::size_t runs = 1;       // window runs in the profile, the front one included
    Node node;                  // the joined run
    double exit_max_m_s = 0.0;  // the bound on its exit
    bool waits = false;         // more of the program may let another run join
  };
  void begin_release(const Merge& merge);
  [[nodiscard]] Merge plan_merge();
  PlannedSegment emit();
  [[nodiscard]] double exit_max(std::size_t i) const noexcept;
  [[nodiscard]] double entry_bound(const Node& node, double exit_max_m_s) const noexcept;

  PathSource& source_;
  MotionLimits limits_;
  PlannerOptions options_;
  std::deque<Member> members_;    // the segments of the window's runs, then those of the open run
  std::deque<Node> window_;
  std::optional<Run> open_;       // the run still being extended (not yet in the window)
  double open_entry_limit_m_s_ = 0.0;
  SpeedLimit open_entry_cause_ = SpeedLimit::rest;
  double last_cap_m_s_ = 0.0;     // speed cap of the last closed run
  SpeedLimit last_cap_cause_ = SpeedLimit::feed;  // arc_speed when that cap is an arc's
  PathSegment previous_;          // the last segment added, and its limits
  SegmentLimits previous_limits_;
  std::optional<Release> release_;
  std::size_t front_index_ = 0;   // run index of window_.front()
  std::size_t pinned_end_ = 0;    // 1 + run index of the last pinned junction's run (0: none)
  double entry_speed_m_s_ = 0.0;  // committed speed at the start of window_.front()
  double clock_s_ = 0.0;
  std::size_t pending_ = 0;       // runs pushed since the last backward pass (at the window's end)
  std::size_t pass_depth_ = 0;    // earlier runs the last backward pass changed
  std::vector<std::pair<double, double>> backward_junctions_;  // plan_merge's (distance, bound) to check again
  std::size_t waiting_front_ = 0;   // 1 + front_index_ and pinned_end_ when plan_merge() last said wait
  std::size_t waiting_pinned_ = 0;
  bool started_ = false;          // a segment has been read
  bool exhausted_ = false;
  PlannerStatistics statistics_;
};

}  // namespace stiffpath::motion
