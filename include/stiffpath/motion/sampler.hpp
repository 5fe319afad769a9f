// Fixed-rate sampling of planned segments (default 2 kHz), one sample at a time, nothing materialised.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>

#include "stiffpath/motion/planned_segment.hpp"

namespace stiffpath::motion {

inline constexpr double default_sample_rate_hz = 2000.0;  //!< the thesis's control rate (fig. 4.3)

//! The planned segments behind a source's latest samples, oldest first (see SampleSource::keep_segments).
using SegmentHistory = std::deque<PlannedSegment>;

//! Something that hands out trajectory samples in time order; nullopt after the last one.
class SlowdownReport;

class SampleSource {
 public:
  virtual ~SampleSource() = default;
  virtual std::optional<TrajectorySample> next() = 0;
  //! Asks the source to keep the planned segments its samples come from: every segment that ends less than
  //! `seconds` before the latest sample, and those after it taken so far, oldest first; call it before the first
  //! next(). nullptr when the source has no segments (samples from elsewhere). A later call only changes `seconds`.
  virtual const SegmentHistory* keep_segments(double seconds) {
    (void)seconds;
    return nullptr;
  }
  //! The time lost to each limit so far, for a planned G-code program (TrajectoryStream); nullptr otherwise.
  [[nodiscard]] virtual const SlowdownReport* slowdowns() const { return nullptr; }
};

//! How many samples a Sampler at `rate_hz` hands out for segments ending at `duration_s`: every
//! t_k = k / rate up to the first at or after the end, i.e. ceil(duration · rate) + 1 (computed with
//! the sampler's own comparison). Saturates at UINT64_MAX for durations beyond any real job.
std::uint64_t sample_count(double duration_s, double rate_hz) noexcept;

//! Samples at t_k = k / rate, k = 0, 1, …, pulling segments from a SegmentSource as time passes,
//! so memory does not grow with the job. The last sample is the first t_k at or after the end of
//! the last segment: the final point, at rest. An empty source gives no samples. Each segment's
//! path_start_m is set as it is taken (the lengths before it, summed in order), so the samples'
//! path_m is the arc length along the whole program.
class Sampler final : public SampleSource {
 public:
  //! Throws stiffpath::Error unless the rate is positive and finite.
  explicit Sampler(SegmentSource& source, double rate_hz = default_sample_rate_hz);

  //! The next sample, or nullopt after the final one.
  std::optional<TrajectorySample> next() override;
  //! Keeps the segments of the last `seconds` (≥ 0) and the current one (SampleSource::keep_segments).
  const SegmentHistory* keep_segments(double seconds) override;
  [[nodiscard]] double rate_hz() const noexcept { return rate_hz_; }
  //! Samples handed out so far.
  [[nodiscard]] std::uint64_t count() const noexcept { return k_; }
  //! Segments pulled from the source so far.
  [[nodiscard]] std::uint64_t segments() const noexcept { return segments_; }

 private:
  void take(std::optional<PlannedSegment> segment);  // the next segment becomes current_

  SegmentSource& source_;
  double rate_hz_;
  std::optional<PlannedSegment> current_;
  std::uint64_t k_ = 0;
  std::uint64_t segments_ = 0;
  double path_m_ = 0.0;         // arc length where the next segment taken starts
  double keep_s_ = -1.0;        // < 0: no history
  SegmentHistory history_;
  bool started_ = false;
  bool done_ = false;
};

}  // namespace stiffpath::motion
