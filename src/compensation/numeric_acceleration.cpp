// Central-difference acceleration and jerk over a five-sample ring, with rest padding at both ends.
#include "stiffpath/compensation/numeric_acceleration.hpp"

namespace stiffpath::compensation {

Vec2 NumericDifferentiator::position(std::int64_t i) const noexcept {
  if (i < 0) return first_position_;
  if (i >= count_) i = count_ - 1;
  return ring_[static_cast<std::size_t>(i % 5)].position_m;
}

TaskSample NumericDifferentiator::differentiated(std::int64_t k) const noexcept {
  TaskSample s = ring_[static_cast<std::size_t>(k % 5)];
  const Vec2 pm2 = position(k - 2), pm1 = position(k - 1), p0 = position(k), pp1 = position(k + 1),
             pp2 = position(k + 2);
  s.acceleration_m_s2 = (pp1 - 2.0 * p0 + pm1) / (dt_ * dt_);
  s.jerk_m_s3 = (pp2 - 2.0 * pp1 + 2.0 * pm1 - pm2) / (2.0 * dt_ * dt_ * dt_);
  s.snap_m_s4 = Vec2::Zero();
  return s;
}

std::optional<TaskSample> NumericDifferentiator::push(const TaskSample& sample) noexcept {
  if (count_ == 0) first_position_ = sample.position_m;
  ring_[static_cast<std::size_t>(count_ % 5)] = sample;
  ++count_;
  if (emitted_ + 2 < count_) return differentiated(emitted_++);
  return std::nullopt;
}

std::optional<TaskSample> NumericDifferentiator::drain() noexcept {
  if (emitted_ < count_) return differentiated(emitted_++);
  return std::nullopt;
}

}  // namespace stiffpath::compensation
