// PathTiming: arc length filtered, restarted at stops, and the point taken back on the planned path.
#include "path_timing.hpp"

#include <algorithm>
#include <cmath>

#include "stiffpath/compensation/path_motion.hpp"
#include "stiffpath/motion/junction.hpp"

namespace stiffpath::job::detail {

using compensation::FilterSample;
using compensation::PlannedPoint;
using compensation::TaskSample;

namespace {

// The arc length and its rates as a filter quantity (s, 0), with the laser, power and line the sample carries.
FilterSample path_sample(const motion::TrajectorySample& s) noexcept {
  FilterSample f;
  f.t_s = s.t_s;
  f.x[0] = Vec2(s.path_m, 0.0);
  f.x[1] = Vec2(s.path_speed_m_s, 0.0);
  f.x[2] = Vec2(s.path_acceleration_m_s2, 0.0);
  f.x[3] = Vec2(s.path_jerk_m_s3, 0.0);
  f.laser_on = s.laser_on;
  f.power = s.power;
  f.line = s.line;
  return f;
}

// How close to a stop an output's arc length must be to count as standing there (m): a few hundred units in the
// last place of the arc length (the running sums' rounding), far below any mark's scale.
double rest_tolerance_m(double s_m) noexcept { return 1e-12 + 1e-13 * std::abs(s_m); }

}  // namespace

PathTiming::PathTiming(motion::SampleSource& source, const motion::SegmentHistory& history,
                       compensation::FilterChain& filters, double rate_hz)
    : source_(source), history_(history), filters_(filters), rate_hz_(rate_hz),
      corner_angle_rad_(motion::JunctionRules{}.corner_angle_rad),
      delay_(filters.rest_samples()) {}

const motion::PlannedSegment* PathTiming::segment(std::size_t index) const noexcept {
  if (history_.empty()) return nullptr;
  const std::size_t first = history_.front().index;
  if (index < first || index - first >= history_.size()) return nullptr;
  return &history_[index - first];
}

bool PathTiming::restarts(const motion::PlannedSegment* before, const motion::PlannedSegment& after) const noexcept {
  if (!(after.entry_speed_m_s > 0.0)) return true;  // the plan stops there
  if (!before || before->path.kind == motion::SegmentKind::dwell || after.path.kind == motion::SegmentKind::dwell) {
    return false;
  }
  // A corner passed at speed (G64 where nothing is blended, e.g. a laser switch): the plan's velocity steps there,
  // by v·2·sin(φ/2) ≤ j·τ², which a filtered speed would not respect.
  return motion::turn_angle_rad(motion::end_tangent(before->path), motion::start_tangent(after.path)) > corner_angle_rad_;
}

const motion::PlannedSegment& PathTiming::segment_at(double s_m) noexcept {
  const std::size_t first = history_.front().index, last = history_.back().index;
  cursor_ = std::clamp(cursor_, first, last);
  const auto at = [&](std::size_t i) -> const motion::PlannedSegment& { return history_[i - first]; };
  const auto end_m = [&](std::size_t i) { return at(i).path_start_m + at(i).path.length_m; };
  while (cursor_ > first && s_m < at(cursor_).path_start_m) --cursor_;
  // Forward past the pieces that end before s, and past a dwell (no length) when a piece starts at s.
  while (cursor_ < last && (s_m > end_m(cursor_) || (at(cursor_).path.length_m <= 0.0 && at(cursor_ + 1).path_start_m <= s_m))) {
    ++cursor_;
  }
  // A dwell where no piece starts: the piece that ends there gives the direction.
  std::size_t i = cursor_;
  while (i > first && at(i).path.length_m <= 0.0 && end_m(i - 1) >= s_m) --i;
  return at(i).path.length_m > 0.0 ? at(i) : at(cursor_);
}

void PathTiming::start_rest(double s_m, const FilterSample& meta, const Vec2& point_m) {
  if (resting_) close_rest();
  resting_ = true;
  rest_m_ = s_m;
  rest_samples_ = 0;
  rest_meta_ = meta;
  rest_point_m_ = point_m;
  rest_fires_ = false;
}

void PathTiming::close_rest() {
  // A laser that fires while it rests (a dwell with the laser on) does so for as long as programmed, since the
  // filtered motion stands there exactly only once the whole delay rests: the rest is longer by the delay.
  const std::int64_t missing = rest_fires_ ? delay_ : delay_ - rest_samples_;
  if (missing > 0) {
    Pending p;
    p.sample = rest_fires_ ? fire_meta_ : rest_meta_;
    p.sample.x = {Vec2(rest_m_, 0.0), Vec2::Zero(), Vec2::Zero(), Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
    p.point.position_m = rest_point_m_;
    p.move_start_m = move_start_m_;
    p.repeat = missing;
    queue_.push_back(p);
  }
  move_start_m_ = rest_m_;
  resting_ = false;
  rest_fires_ = false;
}

void PathTiming::take(const motion::TrajectorySample& s) {
  Pending p;
  p.sample = path_sample(s);
  p.point = {s.position_m, s.velocity_m_s, s.acceleration_m_s2, s.jerk_m_s3};
  const bool at_rest = !(s.path_speed_m_s > 0.0);
  const motion::PlannedSegment* own = segment(s.segment);
  const bool dwelling = own && own->path.kind == motion::SegmentKind::dwell;
  const bool first = !started_;
  if (first) {
    started_ = true;
    resting_ = false;
    move_start_m_ = s.path_m;
    last_segment_ = s.segment;
  }
  // The restarts the plan passed since the last sample: its stops and corners.
  for (std::size_t index = last_segment_ + 1; index <= s.segment; ++index) {
    const motion::PlannedSegment* entered = segment(index);
    const motion::PlannedSegment* before = index > 0 ? segment(index - 1) : nullptr;
    if (!entered || !restarts(before, *entered)) continue;
    if (resting_ && entered->path_start_m == rest_m_) continue;  // the same stop (a dwell's end)
    // While it stands there the laser stays on only if it is on at both sides (a corner inside a contour), and
    // at no power: the program did not ask for the rest, so nothing is burnt while it lasts (as M4 does at rest).
    FilterSample meta;
    meta.laser_on = before && before->path.laser_on && entered->path.laser_on;
    meta.power = 0.0;
    meta.line = entered->path.line;
    start_rest(entered->path_start_m, meta, entered->path.start_m);
  }
  last_segment_ = std::max(last_segment_, s.segment);
  if (at_rest) {
    if (!(resting_ && s.path_m == rest_m_)) {  // where the program starts or ends, or a dwell
      FilterSample meta = p.sample;
      if (!dwelling) {
        meta.laser_on = false;
        meta.power = 0.0;
      }
      start_rest(s.path_m, meta, s.position_m);
    }
    if (!dwelling) {  // a dwell fires as programmed; any other stop as the stop does
      p.sample.laser_on = rest_meta_.laser_on;
      p.sample.power = rest_meta_.power;
      p.sample.line = rest_meta_.line;
    } else if (p.sample.laser_on) {
      rest_fires_ = true;
      fire_meta_ = p.sample;
    }
    ++rest_samples_;
  } else if (resting_) {
    close_rest();
  }
  if (first && resting_) rest_samples_ = std::max(rest_samples_, delay_);  // the filters rest there before it
  p.move_start_m = move_start_m_;
  queue_.push_back(p);
}

TaskSample PathTiming::on_path(const FilterSample& f, double low_m, double high_m) {
  std::array<double, 6> sigma{};
  for (std::size_t i = 0; i < sigma.size(); ++i) sigma[i] = f.x[i].x();
  // Within its move (rounding and the shapers' Taylor steps could pass the stop by a few nm).
  const double s = std::clamp(sigma[0], low_m, std::max(low_m, high_m));
  const motion::PlannedSegment& seg = segment_at(s);
  const double along = s - seg.path_start_m;
  const motion::PathPoint point = motion::point_at(seg.path, along);
  const auto x = compensation::motion_along({point.position_m, point.tangent, point.curvature_1_m}, sigma);
  TaskSample out;
  out.t_s = f.t_s;
  out.position_m = x[0];
  out.velocity_m_s = x[1];
  out.acceleration_m_s2 = x[2];
  out.jerk_m_s3 = x[3];
  out.snap_m_s4 = x[4];
  out.crackle_m_s5 = x[5];
  // Standing at a restart (within rounding of it): what the inputs there carry.
  const double tolerance = rest_tolerance_m(s);
  bool standing = seg.path.length_m <= 0.0;
  if (!standing && along <= tolerance) standing = restarts(seg.index > 0 ? segment(seg.index - 1) : nullptr, seg);
  if (!standing && seg.path.length_m - along <= tolerance) {
    const motion::PlannedSegment* after = segment(seg.index + 1);
    standing = !after || restarts(&seg, *after);
  }
  if (standing) {  // at a stop: what the inputs there carry (a dwell's own laser state, or the stop's)
    out.laser_on = f.laser_on;
    out.power = f.power;
    out.line = f.line;
  } else {  // moving: the segment's own laser state, and its power at the filtered speed (M4 follows it)
    out.laser_on = seg.path.laser_on;
    out.power = motion::power_at(seg.path, std::max(sigma[1], 0.0));
    out.line = seg.path.line;
  }
  return out;
}

bool PathTiming::next(TaskSample& out) {
  while (queue_.empty() && !source_done_) {
    const auto planned = source_.next();
    if (!planned) {
      source_done_ = true;
      break;
    }
    take(*planned);
  }
  if (!queue_.empty()) {
    Pending& p = queue_.front();
    FilterSample in = p.sample;
    in.t_s = static_cast<double>(pushed_++) / rate_hz_;  // the planned time, plus the rests inserted so far
    low_m_ = p.move_start_m;
    high_m_ = in.x[0].x();
    const FilterSample filtered = filters_.push(in, p.point);
    if (--p.repeat == 0) queue_.pop_front();
    out = on_path(filtered, low_m_, high_m_);
    return true;
  }
  const auto tail = filters_.drain_sample();
  if (!tail) return false;
  out = on_path(*tail, low_m_, high_m_);
  return true;
}

}  // namespace stiffpath::job::detail
