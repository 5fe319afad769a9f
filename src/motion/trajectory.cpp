// Trajectory: planned segments in memory, evaluated at any time by binary search on their start times.
#include "stiffpath/motion/trajectory.hpp"

#include <algorithm>

namespace stiffpath::motion {

Trajectory::Trajectory(std::vector<PlannedSegment> segments) : segments_(std::move(segments)) {
  double path_m = 0.0;  // summed in the Sampler's order, so both give the same arc lengths
  for (auto& segment : segments_) {
    segment.path_start_m = path_m;
    path_m += segment.path.length_m;
  }
}

Trajectory Trajectory::plan(PathSource& source, const MotionLimits& limits, const PlannerOptions& options) {
  Planner planner(source, limits, options);
  std::vector<PlannedSegment> segments;
  while (auto segment = planner.next()) segments.push_back(std::move(*segment));
  return Trajectory(std::move(segments));
}

double Trajectory::duration_s() const noexcept { return segments_.empty() ? 0.0 : segments_.back().end_time_s(); }

TrajectorySample Trajectory::evaluate(double t_s) const noexcept {
  if (segments_.empty()) return {};
  // The segment containing t: the last one starting at or before t (a junction belongs to the later).
  auto after = std::upper_bound(segments_.begin(), segments_.end(), t_s,
                                [](double t, const PlannedSegment& s) { return t < s.start_time_s; });
  const PlannedSegment& segment = after == segments_.begin() ? segments_.front() : *(after - 1);
  return motion::evaluate(segment, t_s);
}

std::optional<PlannedSegment> TrajectoryCursor::next() {
  if (next_ >= trajectory_.segments().size()) return std::nullopt;
  return trajectory_.segments()[next_++];
}

}  // namespace stiffpath::motion
