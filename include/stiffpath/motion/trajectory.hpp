// A whole planned program kept in memory: evaluate it at any time, or walk its segments again.
#pragma once

#include <cstddef>
#include <vector>

#include "stiffpath/motion/planned_segment.hpp"
#include "stiffpath/motion/planner.hpp"

namespace stiffpath::motion {

//! All planned segments of a program, in time order (about 250 bytes each). For streaming jobs of
//! any length use the Planner (or TrajectoryStream) with a Sampler instead.
class Trajectory {
 public:
  Trajectory() = default;
  explicit Trajectory(std::vector<PlannedSegment> segments);

  //! Plans every segment of `source` (whole-program look-ahead) and keeps them.
  static Trajectory plan(PathSource& source, const MotionLimits& limits, const PlannerOptions& options = {});

  //! The sample at time t_s; before 0 the start, after the end the final point at rest. An empty
  //! trajectory gives a zero sample.
  [[nodiscard]] TrajectorySample evaluate(double t_s) const noexcept;
  [[nodiscard]] double duration_s() const noexcept;
  [[nodiscard]] const std::vector<PlannedSegment>& segments() const noexcept { return segments_; }
  [[nodiscard]] bool empty() const noexcept { return segments_.empty(); }

 private:
  std::vector<PlannedSegment> segments_;
};

//! Hands out a Trajectory's segments again, as a SegmentSource for a Sampler.
class TrajectoryCursor final : public SegmentSource {
 public:
  explicit TrajectoryCursor(const Trajectory& trajectory) : trajectory_(trajectory) {}
  std::optional<PlannedSegment> next() override;

 private:
  const Trajectory& trajectory_;
  std::size_t next_ = 0;
};

}  // namespace stiffpath::motion
