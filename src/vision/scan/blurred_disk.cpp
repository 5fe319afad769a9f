// The blurred disk: a round spot of radius R convolved with a Gaussian of σ, by one-dimensional quadrature.
#include "blurred_disk.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stiffpath::vision::detail {

namespace {

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

}  // namespace

double blurred_disk(double rho, double radius, double sigma) {
  if (!(radius > 0.0)) return 0.0;
  if (!(sigma > 1e-9)) return rho < radius ? 1.0 : (rho == radius ? 0.5 : 0.0);
  // The point sits at (rho, 0). A chord of the disk at height y spans x ∈ [−√(R² − y²), √(R² − y²)];
  // blurring along x gives Φ((c − rho)/σ) − Φ((−c − rho)/σ), and along y the Gaussian weight φ(y/σ)/σ.
  // With y = R·sin ψ (dy = R·cos ψ dψ, c = R·cos ψ) only |y| ≤ 8σ matters.
  const double psi_max = std::asin(std::min(1.0, 8.0 * sigma / radius));
  constexpr int n = 48;  // Simpson intervals (even): error < 1e-7 for R/σ from 1 to 200
  const double h = 2 * psi_max / n;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double psi = -psi_max + i * h;
    const double y = radius * std::sin(psi), c = radius * std::cos(psi);
    const double weight = std::exp(-0.5 * (y / sigma) * (y / sigma)) / (sigma * std::sqrt(2 * std::numbers::pi));
    const double f = weight * c * (normal_cdf((c - rho) / sigma) - normal_cdf((-c - rho) / sigma));
    sum += f * (i == 0 || i == n ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0));
  }
  return sum * h / 3;
}

}  // namespace stiffpath::vision::detail
