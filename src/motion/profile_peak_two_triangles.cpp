// Profile case: no cruise and neither half at the acceleration limit; the duration is a quartic's root.
#include <algorithm>
#include <cmath>

#include "profile_cases.hpp"

namespace stiffpath::motion::detail {

// With ramp times w (half from v_lo) and u (half from v_hi), both triangles: v_p = v_lo + j·w² =
// v_hi + j·u², and the length is (v_lo + v_p)·w + (v_hi + v_p)·u. In s = w + u (half the duration)
// and d = w − u = (v_hi − v_lo)/(j·s) this is V·s + j·s³/4 − D²/(4·j·s) = L with V = v_hi + v_lo,
// D = v_hi − v_lo, i.e. the quartic s⁴ + (4V/j)·s² − (4L/j)·s − (D/j)² = 0. It is negative at 0 and
// convex for s > 0, so it has one positive root and Newton's method falls onto it from any point above.
double peak_speed_two_triangles(double length_m, double v_hi, double v_lo, double j) noexcept {
  const double p = 4.0 * (v_hi + v_lo) / j, q = 4.0 * length_m / j, r = (v_hi - v_lo) / j;
  // Upper bounds of the root, each from dropping a positive term: without s⁴ a quadratic; without
  // p·s², s⁴ = q·s + r² holds below max((2q)^(1/3), (2r²)^(1/4)), where s⁴ ≥ 2·max(q·s, r²).
  double s = std::max(std::cbrt(2.0 * q), std::sqrt(std::sqrt(2.0) * r));
  if (p > 0.0) s = std::min(s, (q + std::sqrt(q * q + 4.0 * p * r * r)) / (2.0 * p));
  s = descend_to_root(1.0, 0.0, p, -q, -r * r, s);
  // u = (s − d)/2 is the better-conditioned ramp for v_p: an error δ in s moves v_p by 2j·u·δ only.
  const double u = std::max(0.5 * (s - r / s), 0.0);
  return v_hi + j * u * u;
}

}  // namespace stiffpath::motion::detail
