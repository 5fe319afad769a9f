// LineMerger: chains of short G64 lines become one line where all their vertices lie within ε of it.
#include "stiffpath/motion/line_merge.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stiffpath::motion {

namespace {

constexpr double half_pi = 0.5 * std::numbers::pi;

// The angle of v measured from the unit vector `reference`, in (−π, π].
double angle_from(const Vec2& reference, const Vec2& v) noexcept {
  return std::atan2(reference.x() * v.y() - reference.y() * v.x(), reference.dot(v));
}

bool same_attributes(const PathSegment& a, const PathSegment& b) noexcept {
  return a.feed_m_s == b.feed_m_s && a.laser_on == b.laser_on && a.power == b.power &&
         a.dynamic_power == b.dynamic_power && a.merge_tolerance_m == b.merge_tolerance_m &&
         a.blend_tolerance_m == b.blend_tolerance_m && a.mode == b.mode;
}

}  // namespace

LineMerger::LineMerger(PathSource& source) : source_(source) {}

bool LineMerger::mergeable(const PathSegment& s) const noexcept {
  return s.kind == SegmentKind::line && !s.rapid && s.mode == JunctionMode::blend && s.merge_tolerance_m > 0.0 &&
         s.length_m <= merged_chord_tolerances * s.merge_tolerance_m;
}

void LineMerger::start(const PathSegment& s) noexcept {
  chain_ = s;
  chain_lines_ = 1;
  reference_ = (s.end_m - s.start_m) / s.length_m;
  // The first vertex: every direction keeps it within ε if it lies within ε of the start, else the wedge.
  const double epsilon = s.merge_tolerance_m;
  const double half = s.length_m > epsilon ? std::asin(epsilon / s.length_m) : half_pi;
  low_rad_ = -half;
  high_rad_ = half;
}

bool LineMerger::extend(const PathSegment& s) noexcept {
  const PathSegment& c = *chain_;
  if (!same_attributes(c, s) || s.start_m != c.end_m) return false;
  const Vec2 to = s.end_m - c.start_m;
  const double distance = to.norm();
  const double epsilon = c.merge_tolerance_m;
  if (!(distance > 0.0)) return false;
  const double direction = angle_from(reference_, to);
  // The merged line must keep the vertices seen so far within ε, and this line must move forward along it.
  const double step = angle_from(reference_, s.end_m - s.start_m);
  double low = std::max(low_rad_, step - half_pi), high = std::min(high_rad_, step + half_pi);
  if (!(direction >= low && direction <= high)) return false;
  const double half = distance > epsilon ? std::asin(epsilon / distance) : half_pi;
  low = std::max(low, direction - half);
  high = std::min(high, direction + half);
  low_rad_ = low;
  high_rad_ = high;
  chain_->end_m = s.end_m;
  chain_->length_m = distance;
  ++chain_lines_;
  return true;
}

void LineMerger::flush() {
  if (!chain_) return;
  if (chain_lines_ > 1) {
    chain_->blend_tolerance_m = std::max(chain_->blend_tolerance_m - chain_->merge_tolerance_m, 0.0);
    chain_->merged = true;
    ++merged_out_;
  }
  ready_.push_back(*chain_);
  chain_.reset();
  chain_lines_ = 0;
}

std::optional<PathSegment> LineMerger::next() {
  while (ready_.empty() && !exhausted_) {
    std::optional<PathSegment> s = source_.next();
    if (!s) {
      flush();
      exhausted_ = true;
      break;
    }
    if (s->kind == SegmentKind::line) ++lines_in_;
    if (chain_ && mergeable(*s) && extend(*s)) continue;
    flush();
    if (mergeable(*s)) {
      start(*s);
    } else {
      ready_.push_back(*s);
    }
  }
  if (ready_.empty()) return std::nullopt;
  PathSegment out = ready_.front();
  ready_.pop_front();
  return out;
}

}  // namespace stiffpath::motion
