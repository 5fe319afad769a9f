// The look-ahead's two speed rules: the highest admissible entry (backward) and the highest reachable exit (forward).
#include <algorithm>

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
  // falls. The largest fitting exit lies on the rising branch below min(w, x*).
  const double peak = v <= 1.5 * a * a / j ? v / 3.0 : 0.5 * a * a / j;
  double lo = 0.0, hi = std::min(w, peak);
  if (!fits(length_m, lo, v, a, j)) return 0.0;  // not admitted; stop as well as possible
  for (int k = 0; k < 64 && hi - lo > 1e-15 * (1.0 + v); ++k) {
    const double mid = 0.5 * (lo + hi);
    (fits(length_m, mid, v, a, j) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace stiffpath::motion
