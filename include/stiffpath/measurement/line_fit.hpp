// Least-squares straight lines for the linearity checks of displacement against force.
#pragma once

#include <span>

namespace stiffpath::measurement {

//! y ≈ intercept + slope·x by ordinary least squares.
struct LineFit {
  int n = 0;                  //!< number of points
  double slope = 0.0;
  double intercept = 0.0;
  double r2 = 0.0;            //!< coefficient of determination (1 when y is constant and fitted exactly)
  double rms_residual = 0.0;  //!< √(Σ residual² / n)
  double max_residual = 0.0;  //!< max |residual|
};

//! Fits a line; needs n ≥ 2 and x not all equal (else a LineFit with n set and the rest zero).
LineFit fit_line(std::span<const double> x, std::span<const double> y) noexcept;

//! Least-squares slope of y ≈ slope·x through the origin (Σxy / Σx²); 0 when Σx² = 0.
double slope_through_origin(std::span<const double> x, std::span<const double> y) noexcept;

}  // namespace stiffpath::measurement
