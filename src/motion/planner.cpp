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

double Planner::entry_bound(const Node& node, double exit_max_m_s) const noexcept {
  if (node.path.kind == SegmentKind::dwell) return 0.0;
  return max_entry_speed(node.path.length_m, exit_max_m_s, node.limits.max_acceleration_m_s2,
                         node.limits.max_jerk_m_s3);
}

double Planner::exit_max(std::size_t i) const noexcept {
  return i + 1 < window_.size() ? window_[i + 1].entry_max_m_s : 0.0;  // the unknown future: stop
}

void Planner::push(const PathSegment& segment) {
  Node node{segment, segment_limits(segment, limits_), 0.0, 0.0};
  const bool first = window_.empty() && statistics_.segments == 0;
  if (!first) {
    const Node& before = window_.back();
    node.entry_limit_m_s = junction_speed_limit(before.path, before.limits, node.path, node.limits, limits_,
                                                options_.junction);
  }
  window_.push_back(node);
  // Backward pass from the new end: each entry may rise because its exit may now be faster than
  // the stop assumed before. Entries only ever rise, so the pass ends at the first unchanged one.
  for (std::size_t i = window_.size(); i-- > 0;) {
    Node& n = window_[i];
    const double braking = entry_bound(n, exit_max(i));
    const double entry = std::min(n.entry_limit_m_s, braking);
    if (i + 1 < window_.size() && entry <= n.entry_max_m_s) break;
    n.entry_max_m_s = entry;
    if (n.entry_limit_m_s <= braking) pinned_end_ = std::max(pinned_end_, front_index_ + i + 1);
  }
  statistics_.peak_window = std::max(statistics_.peak_window, window_.size());
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
      ++statistics_.forced_releases;
      return release();
    }
    std::optional<PathSegment> segment = source_.next();
    if (!segment) {
      exhausted_ = true;
    } else if (segment->kind == SegmentKind::dwell || segment->length_m > 0.0) {
      push(*segment);
    }
  }
}

}  // namespace stiffpath::motion
