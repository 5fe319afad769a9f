// The laser switched early (or late) by its own delays, so that it lights exactly where the planned path says.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>

#include "stiffpath/compensation/compensator.hpp"

namespace stiffpath::job {

//! The laser's own delays (s): it lights `on_s` after it is switched on and goes dark `off_s` after it is switched
//! off (positive: late; the robot file's laser.on_delay_ms / off_delay_ms, which a calibration plate identifies).
struct LaserDelays {
  double on_s = 0.0;
  double off_s = 0.0;
};

//! Moves each laser switch of a stream of compensation inputs so that a laser with `delays` lights exactly the
//! laser-on path of the stream: a pulse [t1, t2) is switched on at t1 − on_s and off at t2 − off_s, its power with
//! it. Applied after the reference filters, so the switches follow the motion as it will be commanded. The motion
//! is untouched; the delays are rounded to whole samples (0.5 ms at 2 kHz). Before the first sample and after the
//! last the laser is off.
class LaserTiming {
 public:
  //! Throws stiffpath::Error for a delay beyond ±50 ms or a non-positive rate.
  LaserTiming(double rate_hz, LaserDelays delays);
  //! False when both delays round to no sample: the stream passes unchanged.
  [[nodiscard]] bool active() const noexcept { return on_ != 0 || off_ != 0; }
  //! The next sample with its laser switched by the delays, reading the unshifted ones from `pull` (which returns
  //! false after the last); false after the last.
  bool next(compensation::TaskSample& out, const std::function<bool(compensation::TaskSample&)>& pull);

 private:
  [[nodiscard]] const compensation::TaskSample* at(std::int64_t index) const noexcept;  // null outside the stream

  std::int64_t on_ = 0, off_ = 0;  // the delays in samples
  std::int64_t ahead_ = 0, behind_ = 0;
  std::deque<compensation::TaskSample> window_;  // samples first_ … first_ + size − 1
  std::int64_t first_ = 0;  // index of window_.front()
  std::int64_t next_ = 0;   // index of the next sample to hand out
  bool pulled_all_ = false;
};

}  // namespace stiffpath::job
