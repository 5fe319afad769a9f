// Closed forms for 2×2 compliance matrices: principal square root, tip time constant, lowest natural frequency.
#include "stiffpath/compensation/tip_modes.hpp"

#include <cmath>
#include <numbers>

namespace stiffpath::compensation {

Mat2 matrix_sqrt(const Mat2& A) noexcept {
  const double det = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0);
  if (!(det > 0.0) || !std::isfinite(det)) return Mat2::Zero();
  const double s = std::sqrt(det);
  const double u = A(0, 0) + A(1, 1) + 2.0 * s;
  if (!(u > 0.0) || !std::isfinite(u)) return Mat2::Zero();
  const double inverse_t = 1.0 / std::sqrt(u);
  Mat2 out;
  out << (A(0, 0) + s) * inverse_t, A(0, 1) * inverse_t, A(1, 0) * inverse_t, (A(1, 1) + s) * inverse_t;
  return out;
}

Mat2 tip_time_constant(const Mat2& C, double mass_kg, double damping_ratio) noexcept {
  const double factor = 2.0 * damping_ratio * std::sqrt(mass_kg);
  if (!std::isfinite(factor) || !(mass_kg > 0.0)) return Mat2::Zero();
  return factor * matrix_sqrt(C);
}

double lowest_natural_frequency_hz(const Mat2& C, double mass_kg) noexcept {
  const double half_trace = 0.5 * (C(0, 0) + C(1, 1));
  const double det = C(0, 0) * C(1, 1) - C(0, 1) * C(1, 0);
  const double disc = half_trace * half_trace - det;
  // Complex eigenvalues (a non-symmetric fit): their real part stands for both.
  const double largest = disc > 0.0 ? half_trace + std::sqrt(disc) : half_trace;
  const double product = mass_kg * largest;
  if (!(product > 0.0) || !std::isfinite(product)) return 0.0;
  return 1.0 / (2.0 * std::numbers::pi * std::sqrt(product));
}

double lowest_natural_frequency_hz(const compliance::Model& model, double mass_kg,
                                   const compliance::GridBounds& region) noexcept {
  constexpr int n = 9;
  const compliance::GridBounds box = model.bounds();
  double lowest = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) {
      const Vec2 p(region.x_min + (region.x_max - region.x_min) * i / (n - 1),
                   region.y_min + (region.y_max - region.y_min) * k / (n - 1));
      const double f = lowest_natural_frequency_hz(model.compliance(box.clamp(p)), mass_kg);
      if (f > 0.0 && (lowest == 0.0 || f < lowest)) lowest = f;
    }
  }
  return lowest;
}

}  // namespace stiffpath::compensation
