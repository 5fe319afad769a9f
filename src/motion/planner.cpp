// The look-ahead planner: runs of tangent segments in a window, batched backward passes, a forward pass on release.
#include "stiffpath/motion/planner.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>
#include <utility>
#include <vector>

#include "stiffpath/motion/junction.hpp"
#include "stiffpath/motion/segment_limits.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {

Planner::Planner(PathSource& source, const MotionLimits& limits, const PlannerOptions& options)
    : source_(source), limits_(limits), options_(options) {
  validate(limits_);
}

// max_entry_speed with its first term, braking to rest, computed once per run.
double Planner::entry_bound(const Node& node, double exit_max_m_s) const noexcept {
  if (node.dwell) return 0.0;
  return std::max(node.reach_from_rest_m_s,
                  reachable_speed(node.length_m, exit_max_m_s, node.limits.max_acceleration_m_s2, node.limits.max_jerk_m_s3));
}

double Planner::exit_max(std::size_t i) const noexcept {
  return i + 1 < window_.size() ? window_[i + 1].entry_max_m_s : 0.0;  // the unknown future: stop
}

void Planner::add(const PathSegment& segment) {
  const SegmentLimits limits = segment_limits(segment, limits_);
  const double offset = open_ ? open_->length_m : 0.0;
  if (open_ && options_.one_profile_per_run &&
      extend_run(*open_, previous_, previous_limits_, segment, limits, limits_, options_.junction, options_.runs)) {
    members_.push_back({segment, offset});
  } else {
    SpeedLimit cause = SpeedLimit::rest;
    const double junction =
        started_ ? junction_speed_limit(previous_, previous_limits_, segment, limits, limits_, options_.junction, &cause)
                 : 0.0;
    if (open_) close_run();
    open_ = start_run(segment, limits, options_.runs);
    open_entry_limit_m_s_ = junction;
    open_entry_cause_ = cause;
    members_.push_back({segment, 0.0});
  }
  started_ = true;
  previous_ = segment;
  previous_limits_ = limits;
  statistics_.peak_window = std::max(statistics_.peak_window, members_.size());
}

void Planner::close_run() {
  const Run& run = *open_;
  Node node;
  node.members = run.segments;
  node.length_m = run.length_m;
  node.limits = run.low;
  node.high = run.high;
  node.dwell = run.dwell;
  node.dwell_s = run.dwell ? members_.back().path.dwell_s : 0.0;
  node.line = members_[members_.size() - run.segments].path.line;
  // The junction rules bound the speed by both adjacent segments' caps; a run keeps the lowest cap
  // of its segments, so the junction also takes the caps of both runs.
  // Which cap: below every member's feed it is an arc's (or a tangent junction's inside the run).
  const double feed_cap = std::min(limits_.max_velocity_m_s, run.lowest_feed_m_s);
  const SpeedLimit cap_cause = node.limits.max_velocity_m_s < feed_cap ? SpeedLimit::arc_speed : SpeedLimit::feed;
  node.entry_limit_m_s = open_entry_limit_m_s_;
  node.entry_cause = open_entry_cause_;
  if (node.limits.max_velocity_m_s < node.entry_limit_m_s) {
    node.entry_limit_m_s = node.limits.max_velocity_m_s;
    node.entry_cause = cap_cause;
  }
  if (window_.size() + statistics_.runs > 0 && last_cap_m_s_ < node.entry_limit_m_s) {
    node.entry_limit_m_s = last_cap_m_s_;
    node.entry_cause = last_cap_cause_;
  }
  if (!node.dwell) {
    node.reach_from_rest_m_s = reachable_speed(node.length_m, 0.0, node.limits.max_acceleration_m_s2, node.limits.max_jerk_m_s3);
  }
  last_cap_m_s_ = node.dwell ? 0.0 : node.limits.max_velocity_m_s;
  last_cap_cause_ = node.dwell ? SpeedLimit::dwell : cap_cause;
  // A run whose own junction rules bound its entry even if it had to stop at its end is pinned:
  // pass now, so that the runs before it are released without waiting (each run is visited by at
  // most one such pass, the one that releases it).
  const bool pinned = node.entry_limit_m_s <= entry_bound(node, 0.0);
  window_.push_back(node);
  open_.reset();
  ++pending_;
  if (pinned || pending_ > pass_depth_) backward_pass();
}

// Backward pass from the window's end: each entry may rise because its exit may now be faster than
// the stop assumed before. Entries only ever rise, so the pass ends at the first earlier entry that
// does not change. It runs once more new runs have arrived than the last pass changed earlier
// ones: each pass's work on earlier runs (those it changes, and the one it stops at) is then paid
// for by the runs that waited for the next pass; only the last two passes go unpaid. It also runs
// when a pinned run arrives; the runs such a pass changes are final and never visited again. So a
// whole program costs at most 4·runs + 2·(largest window + 1) entry evaluations. Waiting changes
// nothing but when runs are released: the entries reach the same fixed point either way.
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

// Forward pass for the front run: its exit is what the backward pass allows and what can be reached
// from its entry. Solves its profile; its segments are then handed out by emit().
void Planner::begin_release(const Merge& merge) {
  const Node& node = merge.node;
  // The joined runs' segments continue the front run's arc length.
  double offset_m = window_.front().length_m;
  std::size_t member = window_.front().members;
  for (std::size_t k = 1; k < merge.runs; ++k) {
    for (std::size_t i = 0; i < window_[k].members; ++i) members_[member + i].offset_m += offset_m;
    member += window_[k].members;
    offset_m += window_[k].length_m;
  }
  const double exit = node.dwell ? 0.0
                                 : max_exit_speed(node.length_m, entry_speed_m_s_, merge.exit_max_m_s,
                                                  node.limits.max_acceleration_m_s2, node.limits.max_jerk_m_s3);
  Release release;
  release.limits = node.limits;
  release.members_left = node.members;
  release.speed_m_s = entry_speed_m_s_;
  // The rules that bind the speed at the profile's ends (a valley there), for the account of lost time.
  const auto binds = [](double speed, double bound) { return speed >= bound * (1.0 - 1e-9); };
  if (binds(entry_speed_m_s_, node.entry_limit_m_s)) release.entry_limit = node.entry_cause;
  if (merge.runs < window_.size()) {
    if (binds(exit, window_[merge.runs].entry_limit_m_s)) release.exit_limit = window_[merge.runs].entry_cause;
  } else if (exhausted_) {
    release.exit_limit = SpeedLimit::rest;
  }
  if (node.dwell) {
    release.profile.phase_s[3] = node.dwell_s;
    release.profile.duration_s = node.dwell_s;
  } else {
    const ProfileInput input{node.length_m, entry_speed_m_s_, exit, node.limits.max_velocity_m_s,
                             node.limits.max_acceleration_m_s2, node.limits.max_jerk_m_s3};
    const ProfileStatus status = solve_profile(input, release.profile);
    if (status != ProfileStatus::ok) {
      throw std::logic_error(fmt::format("internal planner error at G-code line {}: profile from {} to {} m/s over {} m: {}",
                                         node.line, entry_speed_m_s_, exit, node.length_m, describe(status)));
    }
  }
  release.cruise_start_s = release.profile.phase_s[0] + release.profile.phase_s[1] + release.profile.phase_s[2];
  release.cruise_start_m = release.profile.state_at(release.cruise_start_s).s_m;
  release_ = release;
  entry_speed_m_s_ = exit;
  for (std::size_t k = 0; k < merge.runs; ++k) window_.pop_front();
  front_index_ += merge.runs;
  ++statistics_.runs;
  statistics_.joined_runs += merge.runs - 1;
}

// Once the front run's entry speed is known, the runs after it may join its profile: the
// tangential acceleration then carries across their junctions instead of returning to zero at
// each (on the short arcs of a blended contour that costs more than the junctions' own bounds).
// A run joins when its junction with the profile so far is tangent, the limits stay within the
// run bands (RunRules), the entry speed admits the joined length (braking to the new exit bound
// with the lower limits), and at every junction inside the joined profile its speed stays below
// the junction's bound: at a distance s from its start it is at most fastest_speed_up(s, entry)
// and, counted back from its end, fastest_speed_up(L − s, exit); one of them below the bound
// suffices. Each decision takes only final values, or values whose later rise cannot change it (a
// speed-up to an exit below the bound after it keeps that exit); otherwise `waits` asks next() to
// read on before releasing, so the streamed plan stays that of the whole program.
Planner::Merge Planner::plan_merge() {
  Merge merge;
  merge.node = window_.front();
  merge.exit_max_m_s = exit_max(0);
  Node& node = merge.node;
  if (node.dwell || !options_.one_profile_per_run || !options_.join_runs) return merge;
  const RunRules& rules = options_.runs;
  const double v0 = entry_speed_m_s_;
  std::vector<std::pair<double, double>>& backward = backward_junctions_;
  backward.clear();
  std::size_t member = node.members;                 // index in members_ of the next run's first segment
  while (merge.runs < window_.size()) {
    const Node& next = window_[merge.runs];
    if (next.dwell || merge.runs >= rules.max_joined_runs || node.members + next.members > rules.max_segments) break;
    // The bands hold over all the joined segments, as within one run.
    const SegmentLimits low = lower_limits(node.limits, next.limits), high = higher_limits(node.high, next.high);
    if (!within_run_bands(low, high, rules) || v0 > low.max_velocity_m_s) break;
    const double a = low.max_acceleration_m_s2, j = low.max_jerk_m_s3;
    const PathSegment& last = members_[member - 1].path;
    const PathSegment& first = members_[member].path;
    const double bound = tangent_junction_speed_limit(last, segment_limits(last, limits_), first,
                                                      segment_limits(first, limits_), limits_, options_.junction, a);
    if (!(bound > 0.0)) break;
    const double length = node.length_m + next.length_m;
    const double after = std::min(exit_max(merge.runs), low.max_velocity_m_s);  // the profile's own cap too
    const bool final_after = exhausted_ || pinned_end_ > front_index_ + merge.runs + 1;
    const bool admitted = v0 <= max_entry_speed(length, after, a, j);
    const double exit = admitted ? max_exit_speed(length, v0, after, a, j) : 0.0;
    if (!final_after && !(admitted && exit >= v0 && exit < after)) {
      merge.waits = true;  // a later rise of `after` may still decide it
      break;
    }
    if (!admitted) break;
    // A junction the profile cannot reach from its entry stays so as runs join (the limits only fall);
    // those it cannot reach only counted back from its exit are checked again with each new exit.
    const auto below = [](double reach, double limit) { return reach * (1.0 + 1e-9) <= limit; };
    const bool forward = below(fastest_speed_up(node.length_m, v0, a, j), bound);
    if (!forward) backward.emplace_back(node.length_m, bound);
    if (!std::all_of(backward.begin(), backward.end(), [&](const auto& k) {
          return below(std::min(fastest_speed_up(k.first, v0, a, j), fastest_speed_up(length - k.first, exit, a, j)), k.second);
        })) {
      break;
    }
    node.members += next.members;
    node.length_m = length;
    node.limits = low;
    node.high = high;
    merge.exit_max_m_s = after;
    member += next.members;
    ++merge.runs;
  }
  return merge;
}

// The next segment of the run being released: its share of the run's profile, from where the
// previous one ended to where the profile has covered its end.
PlannedSegment Planner::emit() {
  Release& r = *release_;
  const Member member = members_.front();
  members_.pop_front();
  const bool last = --r.members_left == 0;
  // Where the profile has covered the segment's end: in the cruise phase directly, else time_at.
  const Profile& p = r.profile;
  const double into_cruise_m = member.offset_m + member.path.length_m - r.cruise_start_m;
  const bool cruising = !last && p.peak_velocity_m_s > 0.0 && into_cruise_m >= 0.0 &&
                        into_cruise_m <= p.peak_velocity_m_s * p.phase_s[3];
  const double end_s = last        ? p.duration_s
                       : cruising ? std::min(r.cruise_start_s + into_cruise_m / p.peak_velocity_m_s, p.duration_s)
                                  : p.time_at(member.offset_m + member.path.length_m);
  PlannedSegment planned;
  planned.path = member.path;
  planned.limits = r.limits;
  planned.profile = r.profile;
  planned.start_time_s = clock_s_;
  planned.duration_s = std::max(end_s - r.profile_time_s, 0.0);
  planned.profile_offset_s = r.profile_time_s;
  planned.profile_offset_m = member.offset_m;
  planned.entry_speed_m_s = r.speed_m_s;
  planned.exit_speed_m_s = last ? p.end_velocity_m_s : cruising ? p.peak_velocity_m_s : p.state_at(end_s).v_m_s;
  planned.index = statistics_.segments;
  planned.entry_limit = r.entry_limit;
  planned.exit_limit = r.exit_limit;
  clock_s_ += planned.duration_s;
  r.profile_time_s = end_s;
  r.speed_m_s = planned.exit_speed_m_s;
  ++statistics_.segments;
  if (last) release_.reset();
  return planned;
}

std::optional<PlannedSegment> Planner::next() {
  for (;;) {
    if (release_) return emit();
    // The front run is releasable once the junction after it is final; it waits on while the runs
    // that may join it (plan_merge) need more of the program, asked again once another junction is
    // pinned (a finished program decides everything).
    const bool asked = !exhausted_ && waiting_front_ == front_index_ + 1 && waiting_pinned_ == pinned_end_;
    if (!window_.empty() && (exhausted_ || pinned_end_ > front_index_ + 1) && !asked) {
      const Merge merge = plan_merge();
      if (!merge.waits) {
        begin_release(merge);
        continue;
      }
      waiting_front_ = front_index_ + 1;
      waiting_pinned_ = pinned_end_;
    }
    if (exhausted_) return std::nullopt;
    if (options_.max_lookahead_segments > 0 && members_.size() >= std::max<std::size_t>(options_.max_lookahead_segments, 2)) {
      if (open_) close_run();
      if (pending_ > 0) {
        backward_pass();
        continue;
      }
      statistics_.forced_releases += window_.front().members;
      begin_release(plan_merge());
      continue;
    }
    std::optional<PathSegment> segment = source_.next();
    if (!segment) {
      exhausted_ = true;
      if (open_) close_run();
      if (pending_ > 0) backward_pass();
    } else if (segment->kind == SegmentKind::dwell || segment->length_m > 0.0) {
      add(*segment);
    }
  }
}

}  // namespace stiffpath::motion
