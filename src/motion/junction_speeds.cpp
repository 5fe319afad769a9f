// The look-ahead's two speed rules: the highest admissible entry (backward) and the highest reachable exit (forward).
#include <algorithm>
#include <cmath>
#include <limits>

#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {

namespace {
constexpr double relative_tolerance = 1e-12;

// Whether the speed change between lo ≤ hi fits in the length (judged on speeds, like the solver).
bool fits(double length_m, double lo, double hi, double a, double j) noexcept {
  return hi <= reachable_speed(length_m, lo, a, j) * (1.0 + relative_tolerance);
}
}  // namespace

double max_entry_speed(double length_m, double exit_max_m_s, double max_acceleration_m_s2,
                       double max_jerk_m_s3) noexcept {
  return std::max(reachable_speed(length_m, 0.0, max_acceleration_m_s2, max_jerk_m_s3),
                  reachable_speed(length_m, exit_max_m_s, max_acceleration_m_s2, max_jerk_m_s3));
}

double max_exit_speed(double length_m, double entry_m_s, double exit_max_m_s, double max_acceleration_m_s2,
                      double max_jerk_m_s3) noexcept {
  const double a = max_acceleration_m_s2, j = max_jerk_m_s3, v = entry_m_s;
  const double w = std::min(exit_max_m_s, reachable_speed(length_m, v, a, j));
  if (w >= v || fits(length_m, w, v, a, j)) return w;
  // Braking from v to w needs more than the length, but braking further fits: the distance of a
  // change from x up to v rises with x up to x* (v/3 for a triangle, a²/2j for a trapezoid), then
  // falls. The largest fitting exit lies on the rising branch below min(w, x*), where the distance
  // is concave in x (both pieces are, and they join with the same slope): Newton's method from
  // x = 0, where it fits, climbs onto the root without passing it.
  const double peak = v <= 1.5 * a * a / j ? v / 3.0 : 0.5 * a * a / j;
  const double hi = std::min(w, peak);
  if (!fits(length_m, 0.0, v, a, j)) return 0.0;  // not admitted; stop as well as possible
  double x = 0.0;
  for (int k = 0; k < 100; ++k) {
    const double dv = v - x;
    double distance = 0.0, slope = 0.0;
    if (dv * j <= a * a) {  // triangle: (x + v)·u with u = sqrt((v − x)/j)
      const double u = std::sqrt(dv / j);
      distance = (x + v) * u;
      slope = u > 0.0 ? u - (x + v) / (2.0 * j * u) : 0.0;
    } else {  // trapezoid: (x + v)/2·((v − x)/a + a/j)
      const double t = dv / a + a / j;
      distance = 0.5 * (x + v) * t;
      slope = 0.5 * t - 0.5 * (x + v) / a;
    }
    if (!(slope > 0.0) || distance >= length_m) break;
    const double next = std::min(x + (length_m - distance) / slope, hi);
    if (!(next > x)) break;
    const bool done = next - x <= 4.0 * std::numeric_limits<double>::epsilon() * (1.0 + v);
    if (!fits(length_m, next, v, a, j)) break;  // rounding at the root: keep the last that fits
    x = next;
    if (done || x >= hi) break;
  }
  return x;
}

}  // namespace stiffpath::motion
