// Ordinary least-squares lines (with and without intercept).
#include "stiffpath/measurement/line_fit.hpp"

#include <algorithm>
#include <cmath>

namespace stiffpath::measurement {

LineFit fit_line(std::span<const double> x, std::span<const double> y) noexcept {
  LineFit fit;
  fit.n = static_cast<int>(std::min(x.size(), y.size()));
  if (fit.n < 2) return fit;
  const double n = fit.n;
  double mx = 0.0, my = 0.0;
  for (int i = 0; i < fit.n; ++i) mx += x[i], my += y[i];
  mx /= n;
  my /= n;
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (int i = 0; i < fit.n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (sxx <= 0.0) return fit;
  fit.slope = sxy / sxx;
  fit.intercept = my - fit.slope * mx;
  double sse = 0.0;
  for (int i = 0; i < fit.n; ++i) {
    const double r = y[i] - (fit.intercept + fit.slope * x[i]);
    sse += r * r;
    fit.max_residual = std::max(fit.max_residual, std::abs(r));
  }
  fit.rms_residual = std::sqrt(sse / n);
  fit.r2 = syy > 0.0 ? 1.0 - sse / syy : 1.0;
  return fit;
}

double slope_through_origin(std::span<const double> x, std::span<const double> y) noexcept {
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) sxy += x[i] * y[i], sxx += x[i] * x[i];
  return sxx > 0.0 ? sxy / sxx : 0.0;
}

}  // namespace stiffpath::measurement
