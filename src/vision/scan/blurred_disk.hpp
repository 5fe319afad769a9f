// A round laser spot seen through the scanner's blur: a disk convolved with an isotropic Gaussian; not installed.
#pragma once

namespace stiffpath::vision::detail {

//! Value, at distance `rho` from its centre, of a disk of radius `radius` (coverage 1 inside, 0 outside)
//! blurred by an isotropic Gaussian of σ = `sigma` (all in px). Exact up to quadrature error (< 1e-7):
//! the blur along the chord direction is done in closed form (Φ), across it by Simpson's rule on
//! y = R·sin ψ, which keeps the integrand smooth where the chords shrink to nothing.
double blurred_disk(double rho, double radius, double sigma);

}  // namespace stiffpath::vision::detail
