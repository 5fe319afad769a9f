// The fixed-rate sampler: advances through planned segments as sample times pass them.
#include "stiffpath/motion/sampler.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::motion {

std::uint64_t sample_count(double duration_s, double rate_hz) noexcept {
  if (!(duration_s > 0.0)) return 1;
  const double k = std::ceil(duration_s * rate_hz);
  if (!(k < 1e18)) return UINT64_MAX;
  auto last = static_cast<std::uint64_t>(k);  // the first k with k / rate >= duration, as next() compares
  while (last > 0 && static_cast<double>(last - 1) / rate_hz >= duration_s) --last;
  while (static_cast<double>(last) / rate_hz < duration_s) ++last;
  return last + 1;
}

Sampler::Sampler(SegmentSource& source, double rate_hz) : source_(source), rate_hz_(rate_hz) {
  if (!std::isfinite(rate_hz) || rate_hz <= 0.0) {
    throw Error(fmt::format("sample rate must be a positive finite number of Hz, got {}", rate_hz));
  }
}

const SegmentHistory* Sampler::keep_segments(double seconds) {
  keep_s_ = std::isfinite(seconds) ? std::max(seconds, 0.0) : 0.0;
  return &history_;
}

void Sampler::take(std::optional<PlannedSegment> segment) {
  current_ = std::move(segment);
  if (!current_) return;
  ++segments_;
  current_->path_start_m = path_m_;
  path_m_ += current_->path.length_m;
  if (keep_s_ >= 0.0) history_.push_back(*current_);
}

std::optional<TrajectorySample> Sampler::next() {
  if (done_) return std::nullopt;
  if (!started_) {
    started_ = true;
    take(source_.next());
    if (!current_) {
      done_ = true;
      return std::nullopt;
    }
  }
  const double t = static_cast<double>(k_) / rate_hz_;
  while (t >= current_->end_time_s()) {
    std::optional<PlannedSegment> following = source_.next();
    if (!following) {  // past the end: the final point, at rest
      done_ = true;
      break;
    }
    take(std::move(following));
  }
  // Segments that ended more than keep_s_ before this sample are no longer asked for.
  while (history_.size() > 1 && history_.front().end_time_s() < t - keep_s_) history_.pop_front();
  ++k_;
  return evaluate(*current_, t);
}

}  // namespace stiffpath::motion
