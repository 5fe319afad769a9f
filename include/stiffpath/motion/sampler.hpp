// Fixed-rate sampling of planned segments (default 2 kHz), one sample at a time, nothing materialised.
#pragma once

#include <cstdint>
#include <optional>

#include "stiffpath/motion/planned_segment.hpp"

namespace stiffpath::motion {

inline constexpr double default_sample_rate_hz = 2000.0;  //!< the thesis's control rate (fig. 4.3)

//! Something that hands out trajectory samples in time order; nullopt after the last one.
class SampleSource {
 public:
  virtual ~SampleSource() = default;
  virtual std::optional<TrajectorySample> next() = 0;
};

//! How many samples a Sampler at `rate_hz` hands out for segments ending at `duration_s`: every
//! t_k = k / rate up to the first at or after the end, i.e. ceil(duration · rate) + 1 (computed with
//! the sampler's own comparison). Saturates at UINT64_MAX for durations beyond any real job.
std::uint64_t sample_count(double duration_s, double rate_hz) noexcept;

//! Samples at t_k = k / rate, k = 0, 1, …, pulling segments from a SegmentSource as time passes,
//! so memory does not grow with the job. The last sample is the first t_k at or after the end of
//! the last segment: the final point, at rest. An empty source gives no samples.
class Sampler final : public SampleSource {
 public:
  //! Throws stiffpath::Error unless the rate is positive and finite.
  explicit Sampler(SegmentSource& source, double rate_hz = default_sample_rate_hz);

  //! The next sample, or nullopt after the final one.
  std::optional<TrajectorySample> next() override;
  [[nodiscard]] double rate_hz() const noexcept { return rate_hz_; }
  //! Samples handed out so far.
  [[nodiscard]] std::uint64_t count() const noexcept { return k_; }
  //! Segments pulled from the source so far.
  [[nodiscard]] std::uint64_t segments() const noexcept { return segments_; }

 private:
  SegmentSource& source_;
  double rate_hz_;
  std::optional<PlannedSegment> current_;
  std::uint64_t k_ = 0;
  std::uint64_t segments_ = 0;
  bool started_ = false;
  bool done_ = false;
};

}  // namespace stiffpath::motion
