// The laser switched early (or late) by its own delays, so that it lights exactly where the planned path says.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>

#include "stiffpath/motion/sampler.hpp"

namespace stiffpath::job {

//! Wraps a planned sample stream and moves each laser switch so that a laser that lights `on_delay_s` after it
//! is switched on and goes dark `off_delay_s` after it is switched off (positive: late, the robot file's
//! laser.on_delay_ms / off_delay_ms, which a calibration plate identifies) lights exactly the planned laser-on
//! path: a planned pulse [t1, t2) is switched on at t1 − on_delay and off at t2 − off_delay, its power with it.
//! The motion is untouched; the delays are rounded to whole samples (0.5 ms at 2 kHz). Before the first sample
//! and after the last the laser is off.
class LaserTiming final : public motion::SampleSource {
 public:
  //! Throws stiffpath::Error for a delay beyond ±50 ms or a non-positive rate.
  LaserTiming(std::unique_ptr<motion::SampleSource> source, double rate_hz, double on_delay_s, double off_delay_s);
  std::optional<motion::TrajectorySample> next() override;

 private:
  [[nodiscard]] const motion::TrajectorySample* at(std::int64_t index) const noexcept;  // null outside the stream

  std::unique_ptr<motion::SampleSource> source_;
  std::int64_t on_ = 0, off_ = 0;     // the delays in samples
  std::int64_t ahead_ = 0, behind_ = 0;
  std::deque<motion::TrajectorySample> window_;  // samples first_ … first_ + size − 1
  std::int64_t first_ = 0;    // index of window_.front()
  std::int64_t next_ = 0;     // index of the next sample to hand out
  bool source_done_ = false;
};

}  // namespace stiffpath::job
