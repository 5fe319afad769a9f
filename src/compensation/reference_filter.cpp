// ReferenceFilter: moving average (continuous jerk) and position-following ZV/ZVD shapers on planned samples.
#include "stiffpath/compensation/reference_filter.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "stiffpath/core/error.hpp"

namespace stiffpath::compensation {

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
  ring_.resize(static_cast<std::size_t>(extra_ + 2));
}

TaskSample ReferenceFilter::input(std::int64_t i) const noexcept {
  const auto size = static_cast<std::int64_t>(ring_.size());
  if (i >= 0 && i < count_) return ring_[static_cast<std::size_t>(i % size)];
  TaskSample rest = i < 0 ? first_ : ring_[static_cast<std::size_t>((count_ - 1) % size)];
  rest.t_s = t0_ + static_cast<double>(i) * dt_;
  rest.velocity_m_s = rest.acceleration_m_s2 = rest.jerk_m_s3 = rest.snap_m_s4 = rest.crackle_m_s5 = Vec2::Zero();
  return rest;
}

TaskSample ReferenceFilter::at(double t) const noexcept {
  const auto n = static_cast<std::int64_t>(std::floor((t - t0_) / dt_));
  TaskSample s = input(n);
  const double d = t - (t0_ + static_cast<double>(n) * dt_);
  const Vec2 j = s.jerk_m_s3, sn = s.snap_m_s4, c = s.crackle_m_s5;
  s.position_m += d * (s.velocity_m_s + d / 2 * (s.acceleration_m_s2 + d / 3 * (j + d / 4 * (sn + d / 5 * c))));
  s.velocity_m_s += d * (s.acceleration_m_s2 + d / 2 * (j + d / 3 * (sn + d / 4 * c)));
  s.acceleration_m_s2 += d * (j + d / 2 * (sn + d / 3 * c));
  s.jerk_m_s3 += d * (sn + d / 2 * c);
  s.snap_m_s4 += d * c;
  s.t_s = t;
  return s;
}

double ReferenceFilter::period_s(const Vec2& p) const {
  const double f = frequency_(p);
  const double zeta = options_.damping_ratio;
  // Clamped, not replaced, below the bound: the delays must stay continuous along the path.
  if (!std::isfinite(f)) return max_period_s_;
  return 1.0 / (std::max(f, options_.min_frequency_hz) * std::sqrt(1.0 - zeta * zeta));
}

TaskSample ReferenceFilter::moving_average(std::int64_t k) const noexcept {
  const TaskSample now = input(k), then = input(k - window_);
  const double W = static_cast<double>(window_) * dt_;
  Vec2 sum = -0.5 * (now.position_m + then.position_m);
  for (std::int64_t i = k - window_; i <= k; ++i) sum += input(i).position_m;
  TaskSample out = input(k - window_ / 2);  // laser and line at the centre of the window
  out.t_s = now.t_s;
  // Euler–Maclaurin: ∫ = h·Σ' − h²/12·(p'(b) − p'(a)) + h⁴/720·(p'''(b) − p'''(a)).
  out.position_m = (dt_ * sum - dt_ * dt_ / 12.0 * (now.velocity_m_s - then.velocity_m_s) +
                    std::pow(dt_, 4) / 720.0 * (now.jerk_m_s3 - then.jerk_m_s3)) / W;
  out.velocity_m_s = (now.position_m - then.position_m) / W;
  out.acceleration_m_s2 = (now.velocity_m_s - then.velocity_m_s) / W;
  out.jerk_m_s3 = (now.acceleration_m_s2 - then.acceleration_m_s2) / W;
  out.snap_m_s4 = (now.jerk_m_s3 - then.jerk_m_s3) / W;
  out.crackle_m_s5 = (now.snap_m_s4 - then.snap_m_s4) / W;
  return out;
}

TaskSample ReferenceFilter::shaped(std::int64_t k) const {
  const TaskSample now = input(k);
  const double h = dt_;
  const auto ahead = [&](double d) {
    return now.position_m + d * (now.velocity_m_s + d / 2 * (now.acceleration_m_s2 + d / 3 * now.jerk_m_s3));
  };
  const double g = period_s(now.position_m), g_after = period_s(ahead(h)), g_before = period_s(ahead(-h));
  const double g_dot = (g_after - g_before) / (2.0 * h), g_ddot = (g_after - 2.0 * g + g_before) / (h * h);
  TaskSample out;
  double centre = 0.0;
  for (std::size_t i = 0; i < shares_.size(); ++i) {
    const double A = shares_[i], c = fraction_[i];
    const double u_dot = 1.0 - c * g_dot, u_ddot = -c * g_ddot;
    const TaskSample x = at(now.t_s - c * g);
    out.position_m += A * x.position_m;
    out.velocity_m_s += A * u_dot * x.velocity_m_s;
    out.acceleration_m_s2 += A * (u_dot * u_dot * x.acceleration_m_s2 + u_ddot * x.velocity_m_s);
    out.jerk_m_s3 += A * (u_dot * u_dot * u_dot * x.jerk_m_s3 + 3.0 * u_dot * u_ddot * x.acceleration_m_s2);
    out.snap_m_s4 += A * (std::pow(u_dot, 4) * x.snap_m_s4 + 6.0 * u_dot * u_dot * u_ddot * x.jerk_m_s3 +
                          3.0 * u_ddot * u_ddot * x.acceleration_m_s2);
    out.crackle_m_s5 += A * (std::pow(u_dot, 5) * x.crackle_m_s5 + 10.0 * std::pow(u_dot, 3) * u_ddot * x.snap_m_s4);
    centre += A * c * g;
  }
  const TaskSample middle = input(k - std::llround(centre / dt_));
  out.t_s = now.t_s;
  out.laser_on = middle.laser_on;
  out.line = middle.line;
  return out;
}

TaskSample ReferenceFilter::filtered(std::int64_t k) const {
  switch (options_.kind) {
    case FilterKind::none: return input(k);
    case FilterKind::smooth: return moving_average(k);
    case FilterKind::zv:
    case FilterKind::zvd: return shaped(k);
  }
  return input(k);
}

std::optional<TaskSample> ReferenceFilter::push(const TaskSample& sample) {
  if (count_ == 0) {
    first_ = sample;
    t0_ = sample.t_s;
  }
  ring_[static_cast<std::size_t>(count_ % static_cast<std::int64_t>(ring_.size()))] = sample;
  ++count_;
  return filtered(emitted_++);
}

std::optional<TaskSample> ReferenceFilter::drain() {
  if (count_ == 0 || emitted_ >= count_ + extra_) return std::nullopt;
  return filtered(emitted_++);
}

std::optional<TaskSample> FilterChain::push(const TaskSample& sample) {
  std::optional<TaskSample> s = sample;
  for (auto& f : filters_) s = f.push(*s);
  return s;
}

std::optional<TaskSample> FilterChain::drain() {
  while (draining_ < filters_.size()) {
    std::optional<TaskSample> s = filters_[draining_].drain();
    if (!s) {
      ++draining_;
      continue;
    }
    for (std::size_t i = draining_ + 1; i < filters_.size(); ++i) s = filters_[i].push(*s);
    return s;
  }
  return std::nullopt;
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
