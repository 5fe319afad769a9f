// TaskSource: the compensation's input sample by sample — planned samples, their acceleration source and the reference filters.
#pragma once

#include "stiffpath/compensation/numeric_acceleration.hpp"
#include "stiffpath/compensation/reference_filter.hpp"
#include "stiffpath/core/enum_names.hpp"
#include "stiffpath/motion/sampler.hpp"

namespace stiffpath::job {

//! Where the acceleration for F = −m·a comes from.
enum class AccelerationSource {
  analytic,  //!< from the jerk-limited profile (default)
  numeric,   //!< second numerical derivative of the sampled positions, as in the thesis (§4.3)
};

//! The samples a compensator steps through, in order: the planned samples of `source` (acceleration
//! analytic, or the thesis's numerical second derivative, §4.3), then `filters` (optional; the job
//! lasts their delay longer and ends with their tails). Used by `run` and by the twin alike, so both
//! compensate the same reference.
class TaskSource {
 public:
  TaskSource(motion::SampleSource& source, double rate_hz, AccelerationSource acceleration,
             compensation::FilterChain* filters = nullptr);
  //! The next sample; false once the planned samples and the filters' tails are exhausted.
  bool next(compensation::TaskSample& out);

 private:
  bool next_planned(compensation::TaskSample& out);

  motion::SampleSource& source_;
  AccelerationSource acceleration_;
  compensation::FilterChain* filters_;
  compensation::NumericDifferentiator numeric_;
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
