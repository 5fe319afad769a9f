// SlowdownReport: the time a plan loses against its programmed feeds, by limit, and its slowest stretches.
#include "stiffpath/motion/slowdown.hpp"

#include <algorithm>

#include "stiffpath/motion/segment_limits.hpp"

namespace stiffpath::motion {

namespace {
std::size_t index(SpeedLimit limit) noexcept { return static_cast<std::size_t>(limit); }
}  // namespace

double SlowStretch::lost_total_s() const noexcept {
  double total = 0.0;
  for (const double s : lost_s) total += s;
  return total;
}

SlowdownReport::SlowdownReport(const MotionLimits& limits, std::size_t max_stretches)
    : limits_(limits), max_stretches_(max_stretches) {}

void SlowdownReport::charge(SpeedLimit limit, double seconds) {
  if (!(seconds > 0.0)) return;
  lost_s_[index(limit)] += seconds;
  if (open_) open_->lost_s[index(limit)] += seconds;
}

void SlowdownReport::valley(SpeedLimit limit) {
  charge(limit, pending_s_);
  pending_s_ = 0.0;
  climbing_ = limit;
}

void SlowdownReport::close_stretch() {
  if (!open_) return;
  if (stretches_.size() < max_stretches_) {
    stretches_.push_back(*open_);
  } else if (max_stretches_ > 0) {
    const auto smallest = std::min_element(stretches_.begin(), stretches_.end(), [](const SlowStretch& a, const SlowStretch& b) {
      return a.lost_total_s() < b.lost_total_s();
    });
    if (smallest->lost_total_s() < open_->lost_total_s()) *smallest = *open_;
  }
  open_.reset();
}

void SlowdownReport::add(const PlannedSegment& s) {
  planned_s_ += s.duration_s;
  if (s.path.kind == SegmentKind::dwell) {
    at_feed_s_ += s.path.dwell_s;
    if (open_) open_->duration_s += s.duration_s, open_->programmed_s += s.path.dwell_s;
    valley(SpeedLimit::dwell);
    return;
  }
  const double v_max = limits_.max_velocity_m_s, length = s.path.length_m;
  const double target = s.path.rapid ? v_max : std::min(s.path.feed_m_s, v_max);
  const double programmed = length / target;
  at_feed_s_ += programmed;
  if (!s.path.rapid && s.path.feed_m_s > v_max) feed_above_limit_s_ += length / v_max - length / s.path.feed_m_s;
  const double own = std::min(segment_limits(s.path, limits_).max_velocity_m_s, target);
  const double cap = std::min(s.limits.max_velocity_m_s, own);
  const double arc = own < target ? length / own - programmed : 0.0;
  const double band = cap < own ? length / cap - length / own : 0.0;
  // The profile's speed changes, split at the middle of its cruise (its peak).
  const Profile& p = s.profile;
  const double peak_s = p.phase_s[0] + p.phase_s[1] + p.phase_s[2] + 0.5 * p.phase_s[3];
  const double t0 = s.profile_offset_s, t1 = t0 + s.duration_s, s0 = s.profile_offset_m, s1 = s0 + length;
  double before = 0.0, after = 0.0;
  if (t1 <= peak_s) {
    before = s.duration_s - length / cap;
  } else if (t0 >= peak_s) {
    after = s.duration_s - length / cap;
  } else {
    const double at_peak = p.state_at(peak_s).s_m;
    before = (peak_s - t0) - (at_peak - s0) / cap;
    after = (t1 - peak_s) - (s1 - at_peak) / cap;
  }
  before = std::max(before, 0.0);
  after = std::max(after, 0.0);
  const double lost = arc + band + before + after;
  const bool slowed = lost > std::max(1e-7, 1e-3 * s.duration_s);
  // A stretch is one kind of move: a mark (laser on), a feed move without the laser, or a rapid.
  const int kind = s.path.rapid ? 2 : s.path.laser_on ? 1 : 0;
  if (kind != last_kind_) close_stretch();
  last_kind_ = kind;
  if (slowed && !open_) {
    open_ = SlowStretch{s.path.line, s.path.line, s.start_time_s, 0.0, 0.0, std::min(s.entry_speed_m_s, s.exit_speed_m_s), {}};
  }
  if (open_) {
    open_->first_line = std::min(open_->first_line, s.path.line);
    open_->last_line = std::max(open_->last_line, s.path.line);
    open_->duration_s += s.duration_s;
    open_->programmed_s += programmed;
    open_->lowest_speed_m_s = std::min({open_->lowest_speed_m_s, s.entry_speed_m_s, s.exit_speed_m_s});
  }
  const bool first = s.profile_offset_s == 0.0, last = t1 >= p.duration_s || s1 >= p.length_m;
  if (first && s.entry_limit != SpeedLimit::none) valley(s.entry_limit);
  charge(SpeedLimit::arc_speed, arc);
  charge(SpeedLimit::curvature_step, band);
  charge(climbing_, before);
  pending_s_ += after;
  if (last && s.exit_limit != SpeedLimit::none) valley(s.exit_limit);
  if (!slowed && pending_s_ == 0.0) close_stretch();
}

void SlowdownReport::finish(double programmed_s) {
  if (finished_) return;
  finished_ = true;
  programmed_s_ = programmed_s;
  valley(SpeedLimit::rest);
  close_stretch();
}

std::vector<SlowStretch> SlowdownReport::slowest() const {
  std::vector<SlowStretch> out = stretches_;
  std::sort(out.begin(), out.end(), [](const SlowStretch& a, const SlowStretch& b) { return a.lost_total_s() > b.lost_total_s(); });
  return out;
}

std::optional<PlannedSegment> SlowdownTap::next() {
  std::optional<PlannedSegment> segment = source_.next();
  if (segment) {
    report_.add(*segment);
  } else {
    report_.finish(clock_.programmed_s());
  }
  return segment;
}

std::optional<PathSegment> FeedClock::next() {
  std::optional<PathSegment> s = source_.next();
  if (!s) return s;
  if (s->kind == SegmentKind::dwell) {
    programmed_s_ += s->dwell_s;
  } else if (s->length_m > 0.0) {
    const double v = s->rapid ? limits_.max_velocity_m_s : std::min(s->feed_m_s, limits_.max_velocity_m_s);
    programmed_s_ += s->length_m / v;
  }
  return s;
}

}  // namespace stiffpath::motion
