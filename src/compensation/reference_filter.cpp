// ReferenceFilter: moving average (continuous jerk, O(1) a sample) and position-following ZV/ZVD shapers.
#include "stiffpath/compensation/reference_filter.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include "stiffpath/core/error.hpp"

namespace stiffpath::compensation {

FilterSample point_sample(const TaskSample& s) noexcept {
  FilterSample f;
  f.t_s = s.t_s;
  f.x = {s.position_m, s.velocity_m_s, s.acceleration_m_s2, s.jerk_m_s3, s.snap_m_s4, s.crackle_m_s5};
  f.laser_on = s.laser_on;
  f.power = s.power;
  f.line = s.line;
  return f;
}

TaskSample task_sample(const FilterSample& f) noexcept {
  TaskSample s;
  s.t_s = f.t_s;
  s.position_m = f.x[0];
  s.velocity_m_s = f.x[1];
  s.acceleration_m_s2 = f.x[2];
  s.jerk_m_s3 = f.x[3];
  s.snap_m_s4 = f.x[4];
  s.crackle_m_s5 = f.x[5];
  s.laser_on = f.laser_on;
  s.power = f.power;
  s.line = f.line;
  return s;
}

PlannedPoint planned_point(const TaskSample& s) noexcept {
  return {s.position_m, s.velocity_m_s, s.acceleration_m_s2, s.jerk_m_s3};
}

namespace {
// The sample at rest where `s` is: its rates zero.
FilterSample at_rest(FilterSample s) noexcept {
  for (std::size_t i = 1; i < s.x.size(); ++i) s.x[i] = Vec2::Zero();
  return s;
}
}  // namespace

ReferenceFilter::ReferenceFilter(double rate_hz, ReferenceFilterOptions options, FrequencyAt frequency)
    : options_(options), frequency_(std::move(frequency)) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) throw Error("reference filter: the sample rate must be positive");
  dt_ = 1.0 / rate_hz;
  const double zeta = options_.damping_ratio;
  if (!(zeta >= 0.0 && zeta <= 0.9)) throw Error("reference filter: damping ratio must lie in 0..0.9");
  switch (options_.kind) {
    case FilterKind::none: break;
    case FilterKind::smooth: {
      if (!(options_.smooth_s > 0.0 && options_.smooth_s <= 1.0)) {
        throw Error("reference filter: the moving average's width must lie in (0, 1] s, got " +
                    std::to_string(options_.smooth_s));
      }
      window_ = 2 * std::max<std::int64_t>(1, std::llround(options_.smooth_s / dt_ / 2.0));
      extra_ = window_;
      const double W = static_cast<double>(window_) * dt_;
      inverse_width_ = 1.0 / W;
      sum_weight_ = dt_ / W;
      edge_weight_ = dt_ * dt_ / 12.0 / W;
      jerk_weight_ = dt_ * dt_ * dt_ * dt_ / 720.0 / W;
      break;
    }
    case FilterKind::zv:
    case FilterKind::zvd: {
      if (!frequency_) throw Error("reference filter: a shaper needs the tip's frequency");
      if (!(options_.min_frequency_hz >= 1.0 && options_.min_frequency_hz <= 1e4)) {
        throw Error("reference filter: the tip's lowest frequency must lie in 1..10000 Hz, got " +
                    std::to_string(options_.min_frequency_hz));
      }
      const double K = std::exp(-zeta * std::numbers::pi / std::sqrt(1.0 - zeta * zeta));
      if (options_.kind == FilterKind::zv) {
        shares_ = {1.0 / (1.0 + K), K / (1.0 + K)};
        fraction_ = {0.0, 0.5};
      } else {
        const double n = (1.0 + K) * (1.0 + K);
        shares_ = {1.0 / n, 2.0 * K / n, K * K / n};
        fraction_ = {0.0, 0.5, 1.0};
      }
      max_period_s_ = 1.0 / (options_.min_frequency_hz * std::sqrt(1.0 - zeta * zeta));
      extra_ = static_cast<std::int64_t>(std::ceil(fraction_.back() * max_period_s_ / dt_)) + 1;
      break;
    }
  }
  ring_.resize(std::bit_ceil(static_cast<std::uint64_t>(extra_ + 2)));
  mask_ = ring_.size() - 1;
}

FilterSample ReferenceFilter::at(std::int64_t k, double delay_s) const noexcept {
  const double back = delay_s / dt_;
  const auto steps = static_cast<std::int64_t>(std::ceil(back));  // the sample at or before the instant
  FilterSample s = input(k - steps);
  const double d = (static_cast<double>(steps) - back) * dt_;
  auto& x = s.x;
  x[0] += d * (x[1] + d / 2 * (x[2] + d / 3 * (x[3] + d / 4 * (x[4] + d / 5 * x[5]))));
  x[1] += d * (x[2] + d / 2 * (x[3] + d / 3 * (x[4] + d / 4 * x[5])));
  x[2] += d * (x[3] + d / 2 * (x[4] + d / 3 * x[5]));
  x[3] += d * (x[4] + d / 2 * x[5]);
  x[4] += d * x[5];
  return s;
}

double ReferenceFilter::period_s(const Vec2& p) const {
  const double f = frequency_(p);
  const double zeta = options_.damping_ratio;
  // Clamped, not replaced, below the bound: the delays must stay continuous along the path.
  if (!std::isfinite(f)) return max_period_s_;
  return 1.0 / (std::max(f, options_.min_frequency_hz) * std::sqrt(1.0 - zeta * zeta));
}

FilterSample ReferenceFilter::moving_average(std::int64_t k) noexcept {
  const FilterSample& now = input(k);
  const FilterSample& then = input(k - window_);
  if (k >= fresh_sum_at_) {  // summed afresh every w + 1 samples: the running sum's rounding never accumulates
    sum_ = Vec2::Zero();
    for (std::int64_t i = k - window_; i <= k; ++i) sum_ += input(i).x[0];
    fresh_sum_at_ = k + window_ + 1;
  } else {
    sum_ += now.x[0] - input(k - window_ - 1).x[0];
  }
  const FilterSample& middle = input(k - window_ / 2);  // laser and line at the centre of the window
  FilterSample out;
  out.t_s = now.t_s;
  out.laser_on = middle.laser_on;
  out.power = middle.power;
  out.line = middle.line;
  // Euler–Maclaurin: ∫ = h·Σ' − h²/12·(x'(b) − x'(a)) + h⁴/720·(x'''(b) − x'''(a)).
  out.x[0] = sum_weight_ * (sum_ - 0.5 * (now.x[0] + then.x[0])) - edge_weight_ * (now.x[1] - then.x[1]) +
             jerk_weight_ * (now.x[3] - then.x[3]);
  for (std::size_t i = 1; i < out.x.size(); ++i) out.x[i] = inverse_width_ * (now.x[i - 1] - then.x[i - 1]);
  return out;
}

FilterSample ReferenceFilter::shaped(std::int64_t k) const {
  const PlannedPoint& p = point_;
  const double h = dt_;
  const auto ahead = [&](double d) {
    return p.position_m + d * (p.velocity_m_s + d / 2 * (p.acceleration_m_s2 + d / 3 * p.jerk_m_s3));
  };
  const double g = period_s(p.position_m), g_after = period_s(ahead(h)), g_before = period_s(ahead(-h));
  const double g_dot = (g_after - g_before) / (2.0 * h), g_ddot = (g_after - 2.0 * g + g_before) / (h * h);
  FilterSample out;
  double centre = 0.0;
  for (std::size_t i = 0; i < shares_.size(); ++i) {
    const double A = shares_[i], c = fraction_[i];
    const double u1 = 1.0 - c * g_dot, u2 = -c * g_ddot;
    const double u1_2 = u1 * u1, u1_3 = u1_2 * u1;
    const auto& x = at(k, c * g).x;
    out.x[0] += A * x[0];
    out.x[1] += A * u1 * x[1];
    out.x[2] += A * (u1_2 * x[2] + u2 * x[1]);
    out.x[3] += A * (u1_3 * x[3] + 3.0 * u1 * u2 * x[2]);
    out.x[4] += A * (u1_3 * u1 * x[4] + 6.0 * u1_2 * u2 * x[3] + 3.0 * u2 * u2 * x[2]);
    out.x[5] += A * (u1_3 * u1_2 * x[5] + 10.0 * u1_3 * u2 * x[4]);
    centre += A * c * g;
  }
  const FilterSample& middle = input(k - std::llround(centre / dt_));
  out.t_s = input(k).t_s;
  out.laser_on = middle.laser_on;
  out.power = middle.power;
  out.line = middle.line;
  return out;
}

FilterSample ReferenceFilter::step() {
  const std::int64_t k = emitted_++;
  switch (options_.kind) {
    case FilterKind::none: return input(k);
    case FilterKind::smooth: return moving_average(k);
    case FilterKind::zv:
    case FilterKind::zvd: return shaped(k);
  }
  return input(k);
}

FilterSample ReferenceFilter::push(const FilterSample& sample, const PlannedPoint& point) {
  if (count_ == 0) std::fill(ring_.begin(), ring_.end(), at_rest(sample));  // at rest before the first sample
  ring_[static_cast<std::uint64_t>(count_) & mask_] = sample;
  ++count_;
  point_ = point;
  return step();
}

std::optional<FilterSample> ReferenceFilter::drain_sample() {
  if (count_ == 0 || emitted_ >= count_ + extra_) return std::nullopt;
  // The input rests at its last sample (which the ring keeps: it holds extra_ + 2 samples).
  FilterSample rest = at_rest(input(count_ - 1));
  rest.t_s += static_cast<double>(emitted_ - count_ + 1) * dt_;
  if (emitted_ == count_) point_.velocity_m_s = point_.acceleration_m_s2 = point_.jerk_m_s3 = Vec2::Zero();
  ring_[static_cast<std::uint64_t>(emitted_) & mask_] = rest;
  return step();
}

std::optional<TaskSample> ReferenceFilter::push(const TaskSample& sample) {
  return task_sample(push(point_sample(sample), planned_point(sample)));
}

std::optional<TaskSample> ReferenceFilter::drain() {
  const auto s = drain_sample();
  if (!s) return std::nullopt;
  return task_sample(*s);
}

FilterSample FilterChain::push(const FilterSample& sample, const PlannedPoint& point) {
  point_ = point;
  FilterSample s = sample;
  for (auto& f : filters_) s = f.push(s, point);
  return s;
}

std::optional<FilterSample> FilterChain::drain_sample() {
  point_.velocity_m_s = point_.acceleration_m_s2 = point_.jerk_m_s3 = Vec2::Zero();
  while (draining_ < filters_.size()) {
    std::optional<FilterSample> s = filters_[draining_].drain_sample();
    if (!s) {
      ++draining_;
      continue;
    }
    for (std::size_t i = draining_ + 1; i < filters_.size(); ++i) s = filters_[i].push(*s, point_);
    return s;
  }
  return std::nullopt;
}

std::optional<TaskSample> FilterChain::push(const TaskSample& sample) {
  return task_sample(push(point_sample(sample), planned_point(sample)));
}

std::optional<TaskSample> FilterChain::drain() {
  const auto s = drain_sample();
  if (!s) return std::nullopt;
  return task_sample(*s);
}

std::int64_t FilterChain::delay_samples() const noexcept {
  std::int64_t n = 0;
  for (const auto& f : filters_) n += f.delay_samples();
  return n;
}

std::vector<ReferenceFilter> smoothing_filters(double rate_hz, double width_s) {
  if (!(width_s >= 0.0 && width_s <= 1.0)) {
    throw Error("smoothing width must lie in 0…1000 ms, got " + std::to_string(width_s * 1e3) + " ms");
  }
  std::vector<ReferenceFilter> filters;
  if (width_s > 0.0) {
    ReferenceFilterOptions f;
    f.kind = FilterKind::smooth;
    f.smooth_s = 0.5 * width_s;
    filters.emplace_back(rate_hz, f);
    filters.emplace_back(rate_hz, f);
  }
  return filters;
}

}  // namespace stiffpath::compensation
