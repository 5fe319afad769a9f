// Profile case: no cruise, both halves reach the acceleration limit; the peak speed is a quadratic's root.
#include <cmath>

#include "profile_cases.hpp"

namespace stiffpath::motion::detail {

// Each half is a trapezoid: D_i = (v_p² − v_i²)/(2a) + (v_i + v_p)·a/(2j). Their sum equals L when
// v_p² + v_p·a²/j + C = 0 with C = (v0 + v1)·a²/(2j) − (v0² + v1²)/2 − a·L (C < 0 for a positive root).
double peak_speed_both_trapezoids(double length_m, double v0, double v1, double a, double j) noexcept {
  const double b = a * a / j;
  const double c = 0.5 * (v0 + v1) * b - 0.5 * (v0 * v0 + v1 * v1) - a * length_m;
  return -2.0 * c / (b + std::sqrt(b * b - 4.0 * c));  // the positive root without cancellation
}

}  // namespace stiffpath::motion::detail
