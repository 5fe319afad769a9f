// LaserTiming: each planned laser switch moved earlier by the laser's own delay, the motion untouched.
#include "stiffpath/job/laser_timing.hpp"

#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::job {

LaserTiming::LaserTiming(double rate_hz, LaserDelays delays) {
  const double on_delay_s = delays.on_s, off_delay_s = delays.off_s;
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) throw Error("laser timing: the rate must be positive");
  for (const double d : {on_delay_s, off_delay_s}) {
    if (!(std::abs(d) <= 0.05)) throw Error(fmt::format("laser timing: a delay must lie within ±50 ms, got {} s", d));
  }
  on_ = std::llround(on_delay_s * rate_hz);
  off_ = std::llround(off_delay_s * rate_hz);
  ahead_ = std::max<std::int64_t>({0, on_, off_});
  behind_ = std::max<std::int64_t>({0, -on_, -off_});
}

const compensation::TaskSample* LaserTiming::at(std::int64_t index) const noexcept {
  if (index < first_ || index >= first_ + static_cast<std::int64_t>(window_.size())) return nullptr;
  return &window_[static_cast<std::size_t>(index - first_)];
}

bool LaserTiming::next(compensation::TaskSample& out, const std::function<bool(compensation::TaskSample&)>& pull) {
  // Keep the samples from next − behind to next + ahead.
  while (!pulled_all_ && first_ + static_cast<std::int64_t>(window_.size()) <= next_ + ahead_) {
    compensation::TaskSample s;
    if (pull(s)) {
      window_.push_back(s);
    } else {
      pulled_all_ = true;
    }
  }
  while (first_ < next_ - behind_ && !window_.empty()) {
    window_.pop_front();
    ++first_;
  }
  const compensation::TaskSample* now = at(next_);
  if (!now) return false;
  out = *now;
  // A planned pulse [r, f) is switched on over [r − on, f − off): with the later of the two shifts leading, the
  // sample is on when either shifted look is on; with the earlier, when both are (pulses do not touch).
  const compensation::TaskSample* early = at(next_ + on_);
  const compensation::TaskSample* late = at(next_ + off_);
  const bool lit_on = early && early->laser_on, lit_off = late && late->laser_on;
  out.laser_on = on_ >= off_ ? (lit_on || lit_off) : (lit_on && lit_off);
  out.power = !out.laser_on ? 0.0 : lit_on ? early->power : late->power;
  ++next_;
  return true;
}

}  // namespace stiffpath::job
