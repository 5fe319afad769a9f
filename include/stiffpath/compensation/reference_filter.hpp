// Filters on the planned reference before compensation: a short moving average (continuous jerk) or input shaping.
#pragma once

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

//! A causal FIR filter on a stream of planned samples at a fixed rate (offline stage; not real-time):
//! out(t) = Σᵢ Aᵢ·in(t − τᵢ(t)) for the shapers, out(t) = (1/W)·∫_{t−W}^{t} in for the moving
//! average. Position, velocity, acceleration, jerk and snap are filtered consistently: the moving
//! average's rates are exact differences of the input's (v̄ = (p(t) − p(t−W))/W, …) and its position
//! the Euler–Maclaurin-corrected trapezoid sum; the shapers' delays τᵢ = cᵢ/f_d(p(t)) follow the
//! tip's frequency at the current planned point, and their rates carry the chain rule's factors
//! u̇ = 1 − τ̇ᵢ, ü = −τ̈ᵢ. The input between samples is its Taylor polynomial from the sample before.
//! Before the first sample the robot rests at the first point; after the last, at the last point:
//! the filter hands out `delay_samples()` more samples than it gets (the cycle-time cost).
//! Laser state and G-code line are those of the input at the filter's centre of delay.
class ReferenceFilter {
 public:
  //! Throws stiffpath::Error for a non-positive rate, a width W outside 0…1 s, ζ outside 0…0.9, or a
  //! shaper without a frequency function or with min_frequency_hz outside 1…10000 Hz.
  ReferenceFilter(double rate_hz, ReferenceFilterOptions options, FrequencyAt frequency = {});

  //! Feeds the next planned sample; returns the next filtered one once it is known.
  std::optional<TaskSample> push(const TaskSample& sample);
  //! After the last push: the remaining samples one by one, then nullopt.
  std::optional<TaskSample> drain();
  //! Samples handed out beyond those pushed (the filter's longest delay in samples).
  [[nodiscard]] std::int64_t delay_samples() const noexcept { return extra_; }
  [[nodiscard]] const ReferenceFilterOptions& options() const noexcept { return options_; }

 private:
  [[nodiscard]] TaskSample input(std::int64_t index) const noexcept;  // padded with rest at both ends
  [[nodiscard]] TaskSample at(double t) const noexcept;               // input at any time (Taylor)
  [[nodiscard]] TaskSample filtered(std::int64_t index) const;
  [[nodiscard]] TaskSample moving_average(std::int64_t index) const noexcept;
  [[nodiscard]] TaskSample shaped(std::int64_t index) const;
  [[nodiscard]] double period_s(const Vec2& p) const;  // damped period at p

  double dt_;
  ReferenceFilterOptions options_;
  FrequencyAt frequency_;
  std::int64_t window_ = 0;   // moving average: W in samples (even)
  std::int64_t extra_ = 0;    // samples of history the filter needs, and hands out after the input ends
  std::vector<double> shares_;   // the shaper's impulses: amplitude …
  std::vector<double> fraction_; // … and delay as a fraction of the damped period
  double max_period_s_ = 0.0;    // damped period at min_frequency_hz
  std::vector<TaskSample> ring_;
  TaskSample first_{};
  double t0_ = 0.0;
  std::int64_t count_ = 0;    // samples pushed
  std::int64_t emitted_ = 0;  // samples handed out
  bool ended_ = false;
};

//! Filters applied one after the other (e.g. a shaper, then the moving average); empty: unchanged.
class FilterChain {
 public:
  FilterChain() = default;
  explicit FilterChain(std::vector<ReferenceFilter> filters) : filters_(std::move(filters)) {}
  //! Feeds the next planned sample through every filter; returns the next filtered sample.
  std::optional<TaskSample> push(const TaskSample& sample);
  //! After the last push: the remaining samples (each filter's tail through the later ones), then nullopt.
  std::optional<TaskSample> drain();
  [[nodiscard]] bool empty() const noexcept { return filters_.empty(); }
  //! Samples added to the job in all (the cycle-time cost, in samples).
  [[nodiscard]] std::int64_t delay_samples() const noexcept;

 private:
  std::vector<ReferenceFilter> filters_;
  std::size_t draining_ = 0;  // the filter whose tail is being drained
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
