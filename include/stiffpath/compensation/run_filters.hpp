// The reference filters the offline job puts before compensation (as `stiffpath run`): an input shaper, then smoothing.
#pragma once

#include <memory>

#include "stiffpath/compensation/reference_filter.hpp"
#include "stiffpath/compliance/model.hpp"

namespace stiffpath::compensation {

//! What filters the planned reference gets before compensation. Defaults: those of `stiffpath run`.
struct RunFilterOptions {
  //! Total smoothing width W (s): two moving averages of W/2 each, so that jerk and snap become continuous
  //! and the dynamic offset's terms in a, j and s have no steps. 0: no smoothing. 0 … 1 s.
  double smooth_s = kDefaultSmoothing_s;
  //! FilterKind::none, zv or zvd: an input shaper whose delays follow the tip's natural frequency
  //! (FilterKind::smooth is refused here: see smooth_s).
  FilterKind shaper = FilterKind::none;
  double damping_ratio = 0.05;  //!< ζ the shaper is designed for (that of CompensatorOptions)
  //! The tip's lowest natural frequency on the job (Hz, lowest_natural_frequency_hz over the job's region):
  //! required (> 0) with a shaper, which uses it for points whose own frequency is lower or unknown.
  double min_frequency_hz = 0.0;
};

//! The filter chain for a job sampled at rate_hz: the shaper (its frequency at a point from `model`'s C there,
//! clamped into the model's rectangle, and mass_kg), then the two moving averages. Throws stiffpath::Error
//! for smooth_s outside 0 … 1 s, FilterKind::smooth as shaper, or a shaper without a model or frequency.
FilterChain make_run_filters(double rate_hz, const RunFilterOptions& options,
                             std::shared_ptr<const compliance::Model> model, double mass_kg);

//! The same for a job that covers `region`: a shaper's min_frequency_hz, when not given (0), is the tip's lowest
//! natural frequency over it (lowest_natural_frequency_hz on a 9 × 9 grid), as `stiffpath run` takes it.
FilterChain make_run_filters(double rate_hz, RunFilterOptions options, std::shared_ptr<const compliance::Model> model,
                             double mass_kg, const compliance::GridBounds& region);

}  // namespace stiffpath::compensation
