// Profile case: no cruise and at least one half below the acceleration limit; Newton with a bracket.
#include <cmath>
#include <limits>

#include "profile_cases.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion::detail {

namespace {
// d/dv_p of the distance of one half from v_i up to v_p.
double half_slope(double v_peak, double v_i, double a, double j) noexcept {
  const double dv = v_peak - v_i;
  if (dv * j > a * a) return v_peak / a + 0.5 * a / j;                  // trapezoid
  if (dv <= 0.0) return std::numeric_limits<double>::infinity();        // sqrt's slope at 0
  const double u = std::sqrt(dv / j);                                    // triangle: (v_i + v_p)·u
  return u + (v_i + v_peak) / (2.0 * j * u);
}
}  // namespace

double peak_distance(double v_peak, double v0, double v1, double a, double j) noexcept {
  return speed_change(v0, v_peak, a, j).distance_m + speed_change(v_peak, v1, a, j).distance_m;
}

double peak_speed_numeric(double length_m, double v0, double v1, double a, double j, double lo,
                          double hi) noexcept {
  // f(v) = distance(v) − L is increasing with f(lo) ≤ 0 < f(hi). Newton steps that leave the
  // bracket are replaced by bisection, so the iteration always converges.
  double x = hi;
  for (int iteration = 0; iteration < 100 && hi - lo > 4.0 * std::numeric_limits<double>::epsilon() * hi;
       ++iteration) {
    const double f = peak_distance(x, v0, v1, a, j) - length_m;
    if (f <= 0.0) {
      lo = x;
      if (f >= -1e-15 * length_m) break;
    } else {
      hi = x;
    }
    const double slope = half_slope(x, v0, a, j) + half_slope(x, v1, a, j);
    double next = x - f / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    x = next;
  }
  return lo;
}

}  // namespace stiffpath::motion::detail
