// Jerk-limited speed changes with zero end accelerations: duration/distance and the reachable speed over a length.
#include "stiffpath/motion/speed_change.hpp"

#include <algorithm>
#include <cmath>

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

// Positive root of j·u³ + 2·v0·u − L = 0, u = sqrt(Δv/j): the triangle's distance (2·v0 + Δv)·u = L.
double triangle_ramp_time(double length_m, double v0, double j) noexcept {
  const double p = 2.0 * v0 / j, q = length_m / j;  // u³ + p·u − q = 0
  double u = 0.0;
  if (p <= 0.0) {
    u = std::cbrt(q);
  } else {
    // Trigonometric (hyperbolic) form of Cardano's root for one real root; no cancellation.
    const double k = std::sqrt(p / 3.0);
    u = 2.0 * k * std::sinh(std::asinh(1.5 * q / (p * k)) / 3.0);
  }
  const double f = (u * u + p) * u - q, df = 3.0 * u * u + p;  // one Newton step polishes rounding
  if (df > 0.0) u -= f / df;
  return std::max(u, 0.0);
}

}  // namespace

double reachable_speed(double length_m, double v_from_m_s, double max_acceleration_m_s2,
                       double max_jerk_m_s3) noexcept {
  if (!(length_m > 0.0)) return v_from_m_s;
  const double a = max_acceleration_m_s2, j = max_jerk_m_s3, v0 = v_from_m_s;
  const double u = triangle_ramp_time(length_m, v0, j);
  const double dv_triangle = j * u * u;
  if (dv_triangle * j <= a * a) return v0 + dv_triangle;
  // Trapezoid: (v0 + Δv/2)(Δv/a + a/j) = L  ⇔  Δv² + (2·v0 + a²/j)·Δv + 2a·(v0·a/j − L) = 0.
  const double b = 2.0 * v0 + a * a / j;
  const double c = 2.0 * a * (v0 * a / j - length_m);  // < 0 here, since the triangle did not fit
  const double dv = -2.0 * c / (b + std::sqrt(b * b - 4.0 * c));
  return v0 + dv;
}

}  // namespace stiffpath::motion
