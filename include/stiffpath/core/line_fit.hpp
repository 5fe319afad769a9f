// Straight-line least squares y = slope·x + intercept with its statistics (thesis eqs. 4.9–4.11).
#pragma once

#include <span>

namespace stiffpath::core {

//! Result of a straight-line least-squares fit.
struct LineFit {
  double slope = 0.0;            //!< m, o, s or v of eq. 4.8
  double intercept = 0.0;        //!< n, p, u or w of eq. 4.8
  double slope_stderr = 0.0;     //!< standard error of the slope (0 when n = 2)
  double intercept_stderr = 0.0;
  double r_squared = 0.0;        //!< coefficient of determination (1 for a perfect fit)
  double rms_residual = 0.0;     //!< √(Σ residual² / n), in the unit of y
  double max_residual = 0.0;     //!< max |residual|
  int n = 0;                     //!< points used
};

//! Eq. 4.11, Q = (AᵀA)⁻¹AᵀB with A = [F 1], solved in closed form. Needs n ≥ 2 distinct x values;
//! otherwise returns n < 2 (callers raise the error naming the point).
LineFit fit_line(std::span<const double> x, std::span<const double> y) noexcept;

//! Least-squares slope of y ≈ slope·x through the origin (Σxy / Σx²); 0 when Σx² = 0.
double slope_through_origin(std::span<const double> x, std::span<const double> y) noexcept;

}  // namespace stiffpath::core
