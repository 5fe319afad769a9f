// Jerk-limited speed changes with zero end accelerations: duration/distance and the reachable speed over a length.
#include "stiffpath/motion/speed_change.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stiffpath::motion {

SpeedChange speed_change(double v_from_m_s, double v_to_m_s, double max_acceleration_m_s2,
                         double max_jerk_m_s3) noexcept {
  const double a = max_acceleration_m_s2, j = max_jerk_m_s3;
  const double dv = std::abs(v_to_m_s - v_from_m_s);
  SpeedChange change;
  if (dv * j <= a * a) {  // triangle: the acceleration peaks below the limit
    change.ramp_s = std::sqrt(dv / j);
    change.plateau_s = 0.0;
    change.peak_acceleration_m_s2 = j * change.ramp_s;
  } else {  // trapezoid: ramp to a, hold, ramp down
    change.ramp_s = a / j;
    change.plateau_s = dv / a - a / j;
    change.peak_acceleration_m_s2 = a;
  }
  change.duration_s = 2.0 * change.ramp_s + change.plateau_s;
  change.distance_m = 0.5 * (v_from_m_s + v_to_m_s) * change.duration_s;
  return change;
}

namespace {

// Positive root of j·u³ + 2·v0·u − L = 0, u = sqrt(Δv/j): the triangle's distance (2·v0 + Δv)·u = L,
// for a root known to be at most u_max. u³ + p·u − q is increasing and convex for u > 0, and each of
// q/p, cbrt(q) and u_max lies above its root: Halley's method from the least of them converges onto
// it cubically (three or four steps). q/p is the better start when p·u outweighs u³ there; then the
// cube root is not needed.
double triangle_ramp_time(double length_m, double v0, double j, double u_max) noexcept {
  const double p = 2.0 * v0 / j, q = length_m / j;  // u³ + p·u − q = 0
  const double linear = p > 0.0 ? q / p : u_max;
  double u = linear * linear < p ? std::min(linear, u_max) : std::min({std::cbrt(q), linear, u_max});
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double f = (u * u + p) * u - q;
    const double slope = 3.0 * u * u + p, curvature = 6.0 * u;
    const double denominator = 2.0 * slope * slope - f * curvature;
    if (f == 0.0 || !(denominator > 0.0)) break;
    const double step = 2.0 * f * slope / denominator;
    u -= step;
    if (!(std::abs(step) > 4.0 * std::numeric_limits<double>::epsilon() * u)) break;
  }
  return std::max(u, 0.0);
}

}  // namespace

double reachable_speed(double length_m, double v_from_m_s, double max_acceleration_m_s2,
                       double max_jerk_m_s3) noexcept {
  if (!(length_m > 0.0)) return v_from_m_s;
  const double a = max_acceleration_m_s2, j = max_jerk_m_s3, v0 = v_from_m_s;
  const double ramp_at_limit = a / j;  // the longest triangle: Δv = a²/j over (2·v0 + a²/j)·a/j
  if (length_m <= (2.0 * v0 + a * ramp_at_limit) * ramp_at_limit) {
    const double u = triangle_ramp_time(length_m, v0, j, ramp_at_limit);
    return v0 + j * u * u;
  }
  // Trapezoid: (v0 + Δv/2)(Δv/a + a/j) = L  ⇔  Δv² + (2·v0 + a²/j)·Δv + 2a·(v0·a/j − L) = 0.
  const double b = 2.0 * v0 + a * a / j;
  const double c = 2.0 * a * (v0 * a / j - length_m);  // < 0 here, since the triangle did not fit
  const double dv = -2.0 * c / (b + std::sqrt(b * b - 4.0 * c));
  return v0 + dv;
}

double fastest_speed_up(double distance_m, double v0_m_s, double max_acceleration_m_s2, double max_jerk_m_s3) noexcept {
  const double v0 = v0_m_s, a = max_acceleration_m_s2, j = max_jerk_m_s3;
  if (!(distance_m > 0.0)) return v0;
  const double ramp_s = a / j;
  const double ramp_m = v0 * ramp_s + j * ramp_s * ramp_s * ramp_s / 6.0;
  if (distance_m > ramp_m) {
    const double v1 = v0 + 0.5 * a * ramp_s;
    return std::sqrt(v1 * v1 + 2.0 * a * (distance_m - ramp_m));
  }
  // j·t³/6 + v0·t = s by Newton from above: both starts lie at or above the root and the cubic is
  // convex for t ≥ 0, so every step stays above it.
  double t = std::cbrt(6.0 * distance_m / j);
  if (v0 > 0.0) t = std::min(t, distance_m / v0);
  for (int k = 0; k < 100; ++k) {
    const double step = (j * t * t * t / 6.0 + v0 * t - distance_m) / (0.5 * j * t * t + v0);
    if (!(step > 1e-14 * t)) break;
    t -= step;
  }
  return v0 + 0.5 * j * t * t;
}

}  // namespace stiffpath::motion
