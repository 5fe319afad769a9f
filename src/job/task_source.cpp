// TaskSource: planned samples → acceleration source → reference filters, one sample at a time.
#include "stiffpath/job/task_source.hpp"

#include "stiffpath/job/job.hpp"

namespace stiffpath::job {

TaskSource::TaskSource(motion::SampleSource& source, double rate_hz, AccelerationSource acceleration,
                       compensation::FilterChain* filters)
    : source_(source), acceleration_(acceleration), filters_(filters), numeric_(rate_hz) {}

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

bool TaskSource::next(compensation::TaskSample& out) {
  if (!filters_ || filters_->empty()) return next_planned(out);
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

}  // namespace stiffpath::job
