// TaskSource: the compensation's input sample by sample — planned samples, their acceleration source and the reference filters.
#pragma once

#include <memory>

#include "stiffpath/compensation/numeric_acceleration.hpp"
#include "stiffpath/compensation/reference_filter.hpp"
#include "stiffpath/core/enum_names.hpp"
#include "stiffpath/job/laser_timing.hpp"
#include "stiffpath/motion/sampler.hpp"

namespace stiffpath::job {

namespace detail {
class PathTiming;
}

//! Where the acceleration for F = −m·a comes from.
enum class AccelerationSource {
  analytic,  //!< from the jerk-limited profile (default)
  numeric,   //!< second numerical derivative of the sampled positions, as in the thesis (§4.3)
};

//! The samples a compensator steps through, in order: the planned samples of `source` (acceleration
//! analytic, or the thesis's numerical second derivative, §4.3) through `filters` (optional; the job
//! lasts their delay longer and ends with their tails). Used by `run` and by the twin alike, so both
//! compensate the same reference.
//!
//! When the source keeps its planned segments (a TrajectoryStream or Sampler: SampleSource::keep_segments), the
//! filters act on the timing only: they filter the arc length along the path, and every sample is the planned
//! path's own point at the filtered arc length (its rates by the chain rule on the path's lines and arcs), so no
//! filter moves a point off the planned path and laser and power switch exactly where the path does, when the
//! filtered motion gets there. At every stop of the plan (exact stops, dwells) and every corner it passes at speed
//! (G64 where nothing is blended), the motion rests for the filters' rest_samples() before it moves on, so a move
//! is filtered on its own and a corner is never cut. While it rests the laser stays on if it is on at both sides
//! (one stroke through a corner) but at power 0, since the program did not ask for the rest; a dwell with the laser
//! on fires as long as programmed.
//! The numerical acceleration, if asked for, is then that of the filtered positions. A source without segments
//! (samples from elsewhere) gets the planned point itself filtered (its acceleration source first), which is
//! exact on straight strokes but not at corners or on arcs.
//! Last, the laser's switches are moved by its own delays (LaserTiming), on the filtered samples.
class TaskSource {
 public:
  TaskSource(motion::SampleSource& source, double rate_hz, AccelerationSource acceleration,
             compensation::FilterChain* filters = nullptr, LaserDelays laser = {});
  ~TaskSource();
  TaskSource(const TaskSource&) = delete;
  TaskSource& operator=(const TaskSource&) = delete;
  //! The next sample; false once the planned samples and the filters' tails are exhausted.
  bool next(compensation::TaskSample& out);
  //! True when the filters act on the planned path's arc length (see above).
  [[nodiscard]] bool follows_path() const noexcept { return path_ != nullptr; }

 private:
  bool next_timed(compensation::TaskSample& out);  // before the laser's delays
  bool next_planned(compensation::TaskSample& out);
  bool next_reference(compensation::TaskSample& out);  // planned → (numeric) → filters, or along the path

  motion::SampleSource& source_;
  AccelerationSource acceleration_;
  compensation::FilterChain* filters_;
  compensation::NumericDifferentiator numeric_;
  std::unique_ptr<detail::PathTiming> path_;
  LaserTiming laser_;
  bool source_done_ = false;   // numeric: the source is exhausted, the differentiator hands out its last samples
  bool planned_done_ = false;  // filters: the planned samples are exhausted, the filters hand out their tails
};

}  // namespace stiffpath::job

//! Names at the edges: "analytic", "numeric".
template <>
struct stiffpath::core::EnumNames<stiffpath::job::AccelerationSource> {
  static constexpr std::string_view what = "acceleration source";
  static constexpr std::array<std::pair<job::AccelerationSource, std::string_view>, 2> names{
      {{job::AccelerationSource::analytic, "analytic"}, {job::AccelerationSource::numeric, "numeric"}}};
};
