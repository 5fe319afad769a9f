// LaserTiming: each planned laser switch moved earlier by the laser's own delay, the motion untouched.
#include "stiffpath/job/laser_timing.hpp"

#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::job {

LaserTiming::LaserTiming(std::unique_ptr<motion::SampleSource> source, double rate_hz, double on_delay_s,
                         double off_delay_s)
    : source_(std::move(source)) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) throw Error("laser timing: the rate must be positive");
  for (const double d : {on_delay_s, off_delay_s}) {
    if (!(std::abs(d) <= 0.05)) throw Error(fmt::format("laser timing: a delay must lie within ±50 ms, got {} s", d));
  }
  on_ = std::llround(on_delay_s * rate_hz);
  off_ = std::llround(off_delay_s * rate_hz);
  ahead_ = std::max<std::int64_t>({0, on_, off_});
  behind_ = std::max<std::int64_t>({0, -on_, -off_});
}

const motion::TrajectorySample* LaserTiming::at(std::int64_t index) const noexcept {
  if (index < first_ || index >= first_ + static_cast<std::int64_t>(window_.size())) return nullptr;
  return &window_[static_cast<std::size_t>(index - first_)];
}

std::optional<motion::TrajectorySample> LaserTiming::next() {
  // Keep the samples from next − behind to next + ahead.
  while (!source_done_ && first_ + static_cast<std::int64_t>(window_.size()) <= next_ + ahead_) {
    if (auto s = source_->next()) {
      window_.push_back(*s);
    } else {
      source_done_ = true;
    }
  }
  while (first_ < next_ - behind_ && !window_.empty()) {
    window_.pop_front();
    ++first_;
  }
  const motion::TrajectorySample* now = at(next_);
  if (!now) return std::nullopt;
  motion::TrajectorySample out = *now;
  // A planned pulse [r, f) is switched on over [r − on, f − off): with the later of the two shifts leading, the
  // sample is on when either shifted look is on; with the earlier, when both are (pulses do not touch).
  const motion::TrajectorySample* early = at(next_ + on_);
  const motion::TrajectorySample* late = at(next_ + off_);
  const bool lit_on = early && early->laser_on, lit_off = late && late->laser_on;
  out.laser_on = on_ >= off_ ? (lit_on || lit_off) : (lit_on && lit_off);
  out.power = !out.laser_on ? 0.0 : lit_on ? early->power : late->power;
  ++next_;
  return out;
}

}  // namespace stiffpath::job
