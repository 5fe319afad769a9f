// Closed-form straight-line least squares (the normal equations of eq. 4.11) with fit statistics.
#include "stiffpath/core/line_fit.hpp"

#include <algorithm>

#include <cmath>

namespace stiffpath::core {

LineFit fit_line(std::span<const double> x, std::span<const double> y) noexcept {
  LineFit fit;
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 2) {
    fit.n = static_cast<int>(n);
    return fit;
  }
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (!(sxx > 0.0)) {
    fit.n = 1;  // all x equal: the slope is undetermined
    return fit;
  }
  fit.n = static_cast<int>(n);
  fit.slope = sxy / sxx;
  fit.intercept = my - fit.slope * mx;
  double sse = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = y[i] - (fit.slope * x[i] + fit.intercept);
    sse += r * r;
    fit.max_residual = std::max(fit.max_residual, std::abs(r));
  }
  fit.rms_residual = std::sqrt(sse / static_cast<double>(n));
  fit.r_squared = syy > 0.0 ? 1.0 - sse / syy : 1.0;
  if (n > 2) {
    const double s2 = sse / static_cast<double>(n - 2);
    fit.slope_stderr = std::sqrt(s2 / sxx);
    fit.intercept_stderr = std::sqrt(s2 * (1.0 / static_cast<double>(n) + mx * mx / sxx));
  }
  return fit;
}

double slope_through_origin(std::span<const double> x, std::span<const double> y) noexcept {
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    sxy += x[i] * y[i];
    sxx += x[i] * x[i];
  }
  return sxx > 0.0 ? sxy / sxx : 0.0;
}

}  // namespace stiffpath::core
