// The thesis's acceleration source: second numerical derivative of the sampled positions (§4.3).
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "stiffpath/compensation/samples.hpp"

namespace stiffpath::compensation {

//! Replaces each sample's acceleration and jerk by central differences of the sampled positions,
//! a_k = (p_{k+1} − 2p_k + p_{k−1})/Δt² and j_k = (p_{k+2} − 2p_{k+1} + 2p_{k−1} − p_{k−2})/(2Δt³),
//! as the thesis did offline. It needs two samples of look-ahead, so output lags input by two
//! samples; before the first and after the last sample the robot rests at the end point. Snap is 0.
class NumericDifferentiator {
 public:
  explicit NumericDifferentiator(double rate_hz) : dt_(1.0 / rate_hz) {}

  //! Feeds the next planned sample; returns sample k − 2, differentiated, once sample k is known.
  std::optional<TaskSample> push(const TaskSample& sample) noexcept;
  //! After the last push: the remaining samples one by one, then nullopt.
  std::optional<TaskSample> drain() noexcept;

 private:
  [[nodiscard]] Vec2 position(std::int64_t index) const noexcept;
  [[nodiscard]] TaskSample differentiated(std::int64_t k) const noexcept;

  double dt_;
  std::array<TaskSample, 5> ring_{};  // sample i lives in ring_[i % 5]
  Vec2 first_position_ = Vec2::Zero();
  std::int64_t count_ = 0;    // samples pushed
  std::int64_t emitted_ = 0;  // samples handed out
};

}  // namespace stiffpath::compensation
