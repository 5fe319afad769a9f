// Filters on the planned reference before compensation: a short moving average (continuous jerk) or input shaping.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/compensation/samples.hpp"
#include "stiffpath/core/enum_names.hpp"

namespace stiffpath::compensation {

//! What the filter does to the planned samples.
enum class FilterKind : std::uint8_t {
  none,    //!< samples pass unchanged
  smooth,  //!< moving average over the last W seconds: jerk becomes continuous (snap ≤ 2·j_max/W)
  zv,      //!< ZV input shaper: impulses 1/(1+K), K/(1+K) at 0 and half the damped period
  zvd,     //!< ZVD input shaper: impulses 1, 2K, K² over (1+K)² at 0, half and one damped period
};


//! Settings of a ReferenceFilter. Documented defaults.
struct ReferenceFilterOptions {
  FilterKind kind = FilterKind::none;
  //! Width W of the moving average (s), rounded to an even number of samples (at least 2). A jerk
  //! step becomes a snap of Δj/W; a rest-to-rest corner moves by ~j·(W/2)³/6 (4 ms, 5 g/5 ms: 0.1 µm).
  double smooth_s = 0.004;
  double damping_ratio = 0.05;  //!< ζ the shaper is designed for (K = exp(−ζπ/√(1−ζ²)))
  //! Shapers: the lowest frequency (Hz) the tip has on the job (bounds the delays and the history
  //! kept); > 0, required for zv and zvd. A point whose frequency is lower or unknown uses this one.
  double min_frequency_hz = 0.0;
};

//! The tip's lowest natural frequency (Hz) at a point; the shaper's impulses follow it.
using FrequencyAt = std::function<double(const Vec2& position_m)>;

//! One instant of what a ReferenceFilter filters: a quantity x — the planned point itself, or the arc length
//! along the path as (s, 0) — with its first five time derivatives (SI), and the laser state, power and G-code
//! line the instant carries.
struct FilterSample {
  double t_s = 0.0;
  //! x, ẋ, ẍ, x⃛, x⁗, x⁽⁵⁾
  std::array<Vec2, 6> x = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero(), Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
  bool laser_on = false;
  double power = 0.0;
  int line = 0;
};

//! The planned point at an input's instant and its first three rates: the shapers take the tip's frequency there
//! (and half a sample before and after, from these rates), whatever quantity they filter.
struct PlannedPoint {
  Vec2 position_m = Vec2::Zero();
  Vec2 velocity_m_s = Vec2::Zero();
  Vec2 acceleration_m_s2 = Vec2::Zero();
  Vec2 jerk_m_s3 = Vec2::Zero();
};

//! A task sample as a FilterSample whose quantity is the planned point (x = p, ṗ, p̈, jerk, snap, crackle).
FilterSample point_sample(const TaskSample& sample) noexcept;
//! The inverse of point_sample.
TaskSample task_sample(const FilterSample& sample) noexcept;
//! The planned point of a task sample.
PlannedPoint planned_point(const TaskSample& sample) noexcept;

//! A causal FIR filter on a stream of samples at a fixed rate (offline stage; not real-time):
//! out(t) = Σᵢ Aᵢ·in(t − τᵢ(t)) for the shapers, out(t) = (1/W)·∫_{t−W}^{t} in for the moving
//! average. The quantity and its five rates are filtered consistently: the moving average's rates are
//! exact differences of the input's (v̄ = (x(t) − x(t−W))/W, …) and its value the Euler–Maclaurin-corrected
//! trapezoid sum, kept as a running sum (O(1) a sample; summed afresh every W + 1 samples, so rounding does not
//! accumulate over a job); the shapers' delays τᵢ = cᵢ/f_d(p(t)) follow the tip's frequency at the current
//! planned point, and their rates carry the chain rule's factors u̇ = 1 − τ̇ᵢ, ü = −τ̈ᵢ. The input between samples
//! is its Taylor polynomial from the sample before. Before the first sample the input rests at the first one;
//! after the last, at the last one: the filter hands out `delay_samples()` more samples than it gets (the cycle-
//! time cost), and an output depends on the inputs of the last `delay_samples()` samples only. Laser state,
//! power and G-code line are those of the input at the filter's centre of delay.
class ReferenceFilter {
 public:
  //! Throws stiffpath::Error for a non-positive rate, a width W outside 0…1 s, ζ outside 0…0.9, or a
  //! shaper without a frequency function or with min_frequency_hz outside 1…10000 Hz.
  ReferenceFilter(double rate_hz, ReferenceFilterOptions options, FrequencyAt frequency = {});

  //! Feeds the next sample and the planned point of its instant; returns the filtered sample of that instant.
  FilterSample push(const FilterSample& sample, const PlannedPoint& point);
  //! After the last push: the remaining samples one by one (the input resting at its last sample), then nullopt.
  std::optional<FilterSample> drain_sample();
  //! push() of a task sample's planned point (laser and line from the centre of the delay).
  std::optional<TaskSample> push(const TaskSample& sample);
  //! drain_sample() as task samples.
  std::optional<TaskSample> drain();
  //! Samples handed out beyond those pushed (the filter's longest delay in samples).
  [[nodiscard]] std::int64_t delay_samples() const noexcept { return extra_; }
  [[nodiscard]] const ReferenceFilterOptions& options() const noexcept { return options_; }

 private:
  [[nodiscard]] const FilterSample& input(std::int64_t i) const noexcept {
    return ring_[static_cast<std::uint64_t>(i) & mask_];
  }
  [[nodiscard]] FilterSample at(std::int64_t k, double delay_s) const noexcept;  // the input delay_s before sample k
  FilterSample step();  // the output for sample emitted_, its inputs in the ring
  FilterSample moving_average(std::int64_t k) noexcept;
  [[nodiscard]] FilterSample shaped(std::int64_t k) const;
  [[nodiscard]] double period_s(const Vec2& p) const;  // damped period at p

  double dt_;
  ReferenceFilterOptions options_;
  FrequencyAt frequency_;
  std::int64_t window_ = 0;   // moving average: W in samples (even)
  std::int64_t extra_ = 0;    // samples of history the filter needs, and hands out after the input ends
  double sum_weight_ = 0.0, edge_weight_ = 0.0, jerk_weight_ = 0.0, inverse_width_ = 0.0;  // dt/W, dt²/12W, dt⁴/720W, 1/W
  Vec2 sum_ = Vec2::Zero();        // Σ x over the window's w + 1 samples
  std::int64_t fresh_sum_at_ = 0;  // the next sample at which sum_ is summed afresh
  std::vector<double> shares_;   // the shaper's impulses: amplitude …
  std::vector<double> fraction_; // … and delay as a fraction of the damped period
  double max_period_s_ = 0.0;    // damped period at min_frequency_hz
  std::vector<FilterSample> ring_;  // a power of two long, at least extra_ + 2
  std::uint64_t mask_ = 0;
  PlannedPoint point_;        // of the latest input (at rest after the last one)
  std::int64_t count_ = 0;    // samples pushed
  std::int64_t emitted_ = 0;  // samples handed out
};

//! Filters applied one after the other (e.g. a shaper, then the moving average); empty: unchanged.
//! An output depends on the last delay_samples() + 1 inputs only: an input that rests for rest_samples() at a
//! point gives one output at rest there, and the outputs before and after it do not depend on each other (a
//! restart: job::TaskSource rests that long at every stop of a planned path).
class FilterChain {
 public:
  FilterChain() = default;
  explicit FilterChain(std::vector<ReferenceFilter> filters) : filters_(std::move(filters)) {}
  //! Feeds the next sample through every filter (each shaper takes the tip's frequency at `point`); returns the
  //! filtered sample of the same instant.
  FilterSample push(const FilterSample& sample, const PlannedPoint& point);
  //! After the last push: the remaining samples (each filter's tail through the later ones), then nullopt.
  std::optional<FilterSample> drain_sample();
  //! push() of a task sample's planned point (laser and line from the centre of the delay).
  std::optional<TaskSample> push(const TaskSample& sample);
  //! drain_sample() as task samples.
  std::optional<TaskSample> drain();
  [[nodiscard]] bool empty() const noexcept { return filters_.empty(); }
  //! Samples added to the job in all (the cycle-time cost, in samples).
  [[nodiscard]] std::int64_t delay_samples() const noexcept;
  //! How long an input rests for the filters to restart: delay_samples() + 1 (0 without filters).
  [[nodiscard]] std::int64_t rest_samples() const noexcept { return filters_.empty() ? 0 : delay_samples() + 1; }

 private:
  std::vector<ReferenceFilter> filters_;
  std::size_t draining_ = 0;  // the filter whose tail is being drained
  PlannedPoint point_;        // of the latest input
};

//! The moving-average width `stiffpath run` and the twin's default compensation use (s).
inline constexpr double kDefaultSmoothing_s = 0.008;

//! Two moving averages of W/2 each (W = `width_s`; none for W = 0): jerk and snap of the planned
//! samples become continuous, so the dynamic offset's terms in a, j and s have no steps.
//! Throws stiffpath::Error for W outside 0…1 s.
std::vector<ReferenceFilter> smoothing_filters(double rate_hz, double width_s);

}  // namespace stiffpath::compensation

//! Names at the edges: "none", "smooth", "zv", "zvd".
template <>
struct stiffpath::core::EnumNames<stiffpath::compensation::FilterKind> {
  static constexpr std::string_view what = "reference filter";
  static constexpr std::array<std::pair<compensation::FilterKind, std::string_view>, 4> names{
      {{compensation::FilterKind::none, "none"},
       {compensation::FilterKind::smooth, "smooth"},
       {compensation::FilterKind::zv, "zv"},
       {compensation::FilterKind::zvd, "zvd"}}};
};
