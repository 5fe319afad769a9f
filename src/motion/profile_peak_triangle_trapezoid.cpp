// Profile case: no cruise, a triangle from the higher end speed and a trapezoid from the lower; a quartic in the ramp time.
#include <algorithm>
#include <cmath>

#include "profile_cases.hpp"

namespace stiffpath::motion::detail {

// The half from v_hi is a triangle of ramp time u (v_p = v_hi + j·u², distance 2·v_hi·u + j·u³), the
// half from v_lo a trapezoid ((v_p² − v_lo²)/(2a) + (v_lo + v_p)·a/(2j)). Their sum minus L is
//   j²/(2a)·u⁴ + j·u³ + (j·v_hi/a + a/2)·u² + 2·v_hi·u + c0,   c0 = trapezoid(v_lo → v_hi) − L < 0,
// whose coefficients are positive apart from c0: increasing and convex for u ≥ 0, one positive root.
double peak_speed_triangle_trapezoid(double length_m, double v_hi, double v_lo, double a, double j) noexcept {
  const double c4 = j * j / (2.0 * a), c3 = j, c2 = j * v_hi / a + 0.5 * a, c1 = 2.0 * v_hi;
  const double c0 = 0.5 * (v_hi + v_lo) * ((v_hi - v_lo) / a + a / j) - length_m;
  if (!(c0 < 0.0)) return v_hi;
  // Each term alone reaching −c0 bounds the root from above; the ramp is at most a/j in this case.
  const double m = -c0;
  double u = std::min({a / j, std::sqrt(m / c2), std::cbrt(m / c3), std::sqrt(std::sqrt(m / c4))});
  if (c1 > 0.0) u = std::min(u, m / c1);
  u = descend_to_root(c4, c3, c2, c1, c0, u);
  return v_hi + j * u * u;
}

}  // namespace stiffpath::motion::detail
