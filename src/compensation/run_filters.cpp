// The offline job's reference filters: shaper (tip frequency from the compliance model), then two moving averages.
#include "stiffpath/compensation/run_filters.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>
#include <vector>

#include "stiffpath/compensation/tip_modes.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::compensation {

FilterChain make_run_filters(double rate_hz, const RunFilterOptions& options,
                             std::shared_ptr<const compliance::Model> model, double mass_kg) {
  if (options.shaper == FilterKind::smooth) {
    throw Error("reference shaper: expected none, zv or zvd, got 'smooth' (smoothing has its own width)");
  }
  std::vector<ReferenceFilter> filters;
  if (options.shaper != FilterKind::none) {
    if (!model) throw Error("reference shaper: needs the robot's compliance model");
    if (!(options.min_frequency_hz > 0.0)) {
      throw Error(fmt::format("reference shaper: needs the tip's lowest natural frequency on the job, got {} Hz",
                              options.min_frequency_hz));
    }
    ReferenceFilterOptions f;
    f.kind = options.shaper;
    f.damping_ratio = options.damping_ratio;
    f.min_frequency_hz = options.min_frequency_hz;
    filters.emplace_back(rate_hz, f, [model = std::move(model), mass_kg](const Vec2& p) {
      return lowest_natural_frequency_hz(model->compliance(model->bounds().clamp(p)), mass_kg);
    });
  }
  for (auto& f : smoothing_filters(rate_hz, options.smooth_s)) filters.push_back(std::move(f));  // checks 0 … 1 s
  return FilterChain(std::move(filters));
}

FilterChain make_run_filters(double rate_hz, RunFilterOptions options, std::shared_ptr<const compliance::Model> model,
                             double mass_kg, const compliance::GridBounds& region) {
  if (options.shaper != FilterKind::none && options.min_frequency_hz == 0.0 && model) {
    options.min_frequency_hz = lowest_natural_frequency_hz(*model, mass_kg, region);
  }
  return make_run_filters(rate_hz, options, std::move(model), mass_kg);
}

}  // namespace stiffpath::compensation
