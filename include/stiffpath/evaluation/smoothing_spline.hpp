// Cubic smoothing spline y(t) by penalised regression (Reinsch), the "spline fitting" of thesis §4.6 step iv.
#pragma once

#include <span>
#include <vector>

namespace stiffpath::evaluation {

//! Signed extremes of a spline over an interval.
struct SplineExtremes {
  double min = 0.0;          //!< smallest value (same unit as y)
  double max = 0.0;          //!< largest value
  double max_abs = 0.0;      //!< max(|min|, |max|)
  double t_at_max_abs = 0.0; //!< where |y| is largest
};

//! The natural cubic spline f minimising Σ wᵢ (yᵢ − f(tᵢ))² + α ∫ f''(t)² dt (Reinsch 1967; Green &
//! Silverman 1994, §2.3). The penalty α is set from a cutoff wavelength L_c: on evenly spaced data
//! the spline acts as the filter H(λ) = 1 / (1 + (L_c/λ)⁴) on a wiggle of wavelength λ, so wiggles
//! longer than L_c pass almost unchanged (λ = 3·L_c keeps 98.8 %), λ = L_c is halved, shorter ones
//! are removed. L_c = 0 gives the interpolating natural cubic spline. The system is pentadiagonal
//! and solved in O(n). Outside [front(), back()] the spline continues linearly.
class SmoothingSpline {
 public:
  //! Fits y(t). Points need not be sorted; points with equal t are merged (weights added, values
  //! averaged). Weights default to 1 and must be > 0. Throws stiffpath::Error for non-finite input,
  //! a negative cutoff or no points.
  static SmoothingSpline fit(std::span<const double> t, std::span<const double> y, double cutoff_wavelength,
                             std::span<const double> weights = {});

  [[nodiscard]] double value(double t) const;
  [[nodiscard]] double slope(double t) const;
  [[nodiscard]] double front() const { return t0_; }
  [[nodiscard]] double back() const { return t0_ + scale_ * s_.back(); }
  //! Number of distinct knots (merged points).
  [[nodiscard]] std::size_t size() const { return s_.size(); }
  //! The penalty α in the fit's own units (t, y), for reports and tests.
  [[nodiscard]] double penalty() const { return penalty_; }

  //! ∫ |f(t)| dt over [a, b] ∩ [front(), back()], exact for the piecewise cubic (zero crossings
  //! located, Simpson per piece).
  [[nodiscard]] double integral_abs(double a, double b) const;
  //! Extremes of f on [a, b] ∩ [front(), back()] (knots and the cubic pieces' stationary points).
  [[nodiscard]] SplineExtremes extremes(double a, double b) const;

 private:
  struct Cubic {  // f = c0 + c1·u + c2·u² + c3·u³ with u = s − s_i, in the scaled parameter s
    double c0, c1, c2, c3;
    [[nodiscard]] double operator()(double u) const { return c0 + u * (c1 + u * (c2 + u * c3)); }
    [[nodiscard]] double derivative(double u) const { return c1 + u * (2.0 * c2 + u * 3.0 * c3); }
  };
  [[nodiscard]] Cubic piece(std::size_t i) const;
  [[nodiscard]] std::size_t interval(double s) const;
  template <class Visit>
  void for_each_piece(double a, double b, Visit&& visit) const;

  double t0_ = 0.0, scale_ = 1.0, penalty_ = 0.0;  // t = t0_ + scale_·s, scale_ = mean knot spacing
  std::vector<double> s_, g_, gamma_;              // knots (scaled), fitted values, f'' with respect to s
};

}  // namespace stiffpath::evaluation
