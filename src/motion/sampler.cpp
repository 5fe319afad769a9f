// The fixed-rate sampler: advances through planned segments as sample times pass them.
#include "stiffpath/motion/sampler.hpp"

#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::motion {

Sampler::Sampler(SegmentSource& source, double rate_hz) : source_(source), rate_hz_(rate_hz) {
  if (!std::isfinite(rate_hz) || rate_hz <= 0.0) {
    throw Error(fmt::format("sample rate must be a positive finite number of Hz, got {}", rate_hz));
  }
}

std::optional<TrajectorySample> Sampler::next() {
  if (done_) return std::nullopt;
  if (!started_) {
    started_ = true;
    current_ = source_.next();
    if (!current_) {
      done_ = true;
      return std::nullopt;
    }
    ++segments_;
  }
  const double t = static_cast<double>(k_) / rate_hz_;
  while (t >= current_->end_time_s()) {
    std::optional<PlannedSegment> following = source_.next();
    if (!following) {  // past the end: the final point, at rest
      done_ = true;
      break;
    }
    current_ = std::move(following);
    ++segments_;
  }
  ++k_;
  return evaluate(*current_, t);
}

}  // namespace stiffpath::motion
