// The look-ahead planner: a window of segments with incremental backward passes and a forward pass on release.
#include "stiffpath/motion/planner.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {

Planner::Planner(PathSource& source, const MotionLimits& limits, const PlannerOptions& options)
    : source_(source), limits_(limits), options_(options) {
  validate(limits_);
}

// max_entry_speed with its first term, braking to rest, computed once per segment.
double Planner::entry_bound(const Node& node, double exit_max_m_s) const noexcept {
  if (node.path.kind == SegmentKind::dwell) return 0.0;
  return std::max(node.reach_from_rest_m_s, reachable_speed(node.path.length_m, exit_max_m_s,
                                                            node.limits.max_acceleration_m_s2,
                                                            node.limits.max_jerk_m_s3));
}

double Planner::exit_max(std::size_t i) const noexcept {
  return i + 1 < window_.size() ? window_[i + 1].entry_max_m_s : 0.0;  // the unknown future: stop
}

void Planner::push(const PathSegment& segment) {
  Node node{segment, segment_limits(segment, limits_), 0.0, 0.0, 0.0};
  const bool first = window_.empty() && statistics_.segments == 0;
  if (!first) {
    const Node& before = window_.back();
    node.entry_limit_m_s = junction_speed_limit(before.path, before.limits, node.path, node.limits, limits_,
                                                options_.junction);
  }
  if (node.path.kind != SegmentKind::dwell) {
    node.reach_from_rest_m_s =
        reachable_speed(node.path.length_m, 0.0, node.limits.max_acceleration_m_s2, node.limits.max_jerk_m_s3);
  }
  window_.push_back(node);
  ++pending_;
  statistics_.peak_window = std::max(statistics_.peak_window, window_.size());
}

// Backward pass from the window's end: each entry may rise because its exit may now be faster than
// the stop assumed before. Entries only ever rise, so the pass ends at the first earlier entry that
// does not change. It runs once more new segments have arrived than the last pass changed earlier
// ones: each pass's work on earlier segments (those it changes, and the one it stops at) is then
// paid for by the segments that waited for the next pass. Only the last two passes go unpaid, so a
// whole program costs at most 2·(segments + largest window + 1) entry evaluations. Waiting changes
// nothing but when segments are released: the entries reach the same fixed point either way.
void Planner::backward_pass() {
  const std::size_t first_pending = window_.size() - pending_;
  std::size_t changed = 0;
  for (std::size_t i = window_.size(); i-- > 0;) {
    Node& n = window_[i];
    const double braking = entry_bound(n, exit_max(i));
    ++statistics_.entry_evaluations;
    const double entry = std::min(n.entry_limit_m_s, braking);
    if (i < first_pending) {
      if (entry <= n.entry_max_m_s) break;
      ++changed;
    }
    n.entry_max_m_s = entry;
    if (n.entry_limit_m_s <= braking) pinned_end_ = std::max(pinned_end_, front_index_ + i + 1);
  }
  pending_ = 0;
  pass_depth_ = changed;
}

PlannedSegment Planner::release() {
  Node& node = window_.front();
  // Forward pass: the exit is what the backward pass allows and what can be reached from the entry.
  const bool dwell = node.path.kind == SegmentKind::dwell;
  const double exit = dwell ? 0.0
                            : max_exit_speed(node.path.length_m, entry_speed_m_s_, exit_max(0),
                                             node.limits.max_acceleration_m_s2, node.limits.max_jerk_m_s3);
  PlannedSegment planned;
  planned.path = node.path;
  planned.limits = node.limits;
  planned.start_time_s = clock_s_;
  planned.index = front_index_;
  if (dwell) {
    planned.profile.phase_s[3] = node.path.dwell_s;
    planned.profile.duration_s = node.path.dwell_s;
  } else {
    const ProfileInput input{node.path.length_m,        entry_speed_m_s_,
                             exit,                      node.limits.max_velocity_m_s,
                             node.limits.max_acceleration_m_s2, node.limits.max_jerk_m_s3};
    const ProfileStatus status = solve_profile(input, planned.profile);
    if (status != ProfileStatus::ok) {
      throw std::logic_error(fmt::format("internal planner error at G-code line {}: profile from {} to {} m/s over {} m: {}",
                              node.path.line, entry_speed_m_s_, exit, node.path.length_m, describe(status)));
    }
  }
  clock_s_ += planned.profile.duration_s;
  entry_speed_m_s_ = exit;
  window_.pop_front();
  ++front_index_;
  ++statistics_.segments;
  return planned;
}

std::optional<PlannedSegment> Planner::next() {
  for (;;) {
    if (!window_.empty() && (exhausted_ || pinned_end_ > front_index_ + 1)) return release();
    if (exhausted_) return std::nullopt;
    if (options_.max_lookahead_segments > 0 && window_.size() >= std::max<std::size_t>(options_.max_lookahead_segments, 2)) {
      if (pending_ > 0) {
        backward_pass();
        continue;
      }
      ++statistics_.forced_releases;
      return release();
    }
    std::optional<PathSegment> segment = source_.next();
    if (!segment) {
      exhausted_ = true;
      if (pending_ > 0) backward_pass();
    } else if (segment->kind == SegmentKind::dwell || segment->length_m > 0.0) {
      push(*segment);
      if (pending_ > pass_depth_) backward_pass();
    }
  }
}

}  // namespace stiffpath::motion
