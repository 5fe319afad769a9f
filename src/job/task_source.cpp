// TaskSource: planned samples → acceleration source → reference filters (on the path's arc length when it can).
#include "stiffpath/job/task_source.hpp"

#include "path_timing.hpp"
#include "stiffpath/job/job.hpp"

namespace stiffpath::job {

TaskSource::TaskSource(motion::SampleSource& source, double rate_hz, AccelerationSource acceleration,
                       compensation::FilterChain* filters, LaserDelays laser)
    : source_(source), acceleration_(acceleration), filters_(filters), numeric_(rate_hz), laser_(rate_hz, laser) {
  if (filters_ && !filters_->empty()) {
    // The filtered arc length lags the planned one by at most the filters' delay: segments that old are kept.
    const double keep_s = static_cast<double>(filters_->delay_samples() + 3) / rate_hz;
    if (const motion::SegmentHistory* history = source_.keep_segments(keep_s)) {
      path_ = std::make_unique<detail::PathTiming>(source_, *history, *filters_, rate_hz);
    }
  }
}

TaskSource::~TaskSource() = default;

bool TaskSource::next_planned(compensation::TaskSample& out) {
  if (acceleration_ == AccelerationSource::analytic) {
    const auto sample = source_.next();
    if (sample) out = to_task_sample(*sample);
    return sample.has_value();
  }
  while (!source_done_) {
    const auto sample = source_.next();
    if (!sample) {
      source_done_ = true;
    } else if (const auto ready = numeric_.push(to_task_sample(*sample))) {
      out = *ready;
      return true;
    }
  }
  const auto rest = numeric_.drain();
  if (rest) out = *rest;
  return rest.has_value();
}

bool TaskSource::next_reference(compensation::TaskSample& out) {
  if (!planned_done_) {
    compensation::TaskSample planned;
    if (next_planned(planned)) {
      out = *filters_->push(planned);
      return true;
    }
    planned_done_ = true;
  }
  const auto tail = filters_->drain();
  if (tail) out = *tail;
  return tail.has_value();
}

bool TaskSource::next(compensation::TaskSample& out) {
  if (!laser_.active()) return next_timed(out);
  return laser_.next(out, [this](compensation::TaskSample& s) { return next_timed(s); });
}

bool TaskSource::next_timed(compensation::TaskSample& out) {
  if (!filters_ || filters_->empty()) return next_planned(out);
  if (!path_) return next_reference(out);
  if (acceleration_ == AccelerationSource::analytic) return path_->next(out);
  // The thesis's numerical acceleration of the filtered positions.
  while (!source_done_) {
    compensation::TaskSample filtered;
    if (!path_->next(filtered)) {
      source_done_ = true;
    } else if (const auto ready = numeric_.push(filtered)) {
      out = *ready;
      return true;
    }
  }
  const auto rest = numeric_.drain();
  if (rest) out = *rest;
  return rest.has_value();
}

}  // namespace stiffpath::job
