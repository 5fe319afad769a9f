// Profile case: no cruise and at least one half below the acceleration limit; Newton in the ramp time.
#include <algorithm>
#include <cmath>
#include <limits>

#include "profile_cases.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion::detail {

double peak_distance(double v_peak, double v0, double v1, double a, double j) noexcept {
  return speed_change(v0, v_peak, a, j).distance_m + speed_change(v_peak, v1, a, j).distance_m;
}

namespace {

// Distance of both halves and its derivative as functions of u = sqrt((v_p − v_hi)/j), the ramp
// time of the half that starts from the higher end speed v_hi. In this case that half is a
// triangle, (2·v_hi + j·u²)·u, so the distance is smooth and convex in u, unlike in v_p where
// the square roots of the triangles make Newton's method crawl.
struct DistanceInU {
  double value, slope;
};

DistanceInU distance_in_u(double u, double v_hi, double v_lo, double a, double j) noexcept {
  const double vp = v_hi + j * u * u, dvp_du = 2.0 * j * u;
  DistanceInU d{(2.0 * v_hi + j * u * u) * u, 2.0 * v_hi + 3.0 * j * u * u};
  const double dv = vp - v_lo;
  if (dv * j > a * a) {  // the other half reaches the acceleration limit: a trapezoid
    d.value += (vp * vp - v_lo * v_lo) / (2.0 * a) + (v_lo + vp) * a / (2.0 * j);
    d.slope += (vp / a + a / (2.0 * j)) * dvp_du;
  } else {  // a triangle of ramp time w = sqrt((v_p − v_lo)/j) = sqrt((v_hi − v_lo)/j + u²)
    const double w = std::sqrt(dv / j);
    d.value += (v_lo + vp) * w;
    d.slope += dvp_du * w + (w > 0.0 ? (v_lo + vp) * u / w : 2.0 * v_lo);
  }
  return d;
}

}  // namespace

double peak_speed_numeric(double length_m, double v0, double v1, double a, double j, double lo,
                          double hi) noexcept {
  const double v_hi = std::max(v0, v1), v_lo = std::min(v0, v1);
  double u_lo = std::sqrt(std::max(lo - v_hi, 0.0) / j), u_hi = std::sqrt(std::max(hi - v_hi, 0.0) / j);
  // Newton from the right end of the bracket; steps that leave the bracket are bisected instead.
  double u = u_hi;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const DistanceInU d = distance_in_u(u, v_hi, v_lo, a, j);
    const double f = d.value - length_m;
    if (f <= 0.0) {
      u_lo = u;
      if (f >= -1e-15 * length_m) break;
    } else {
      u_hi = u;
    }
    if (u_hi - u_lo <= 4.0 * std::numeric_limits<double>::epsilon() * u_hi) break;
    double next = d.slope > 0.0 ? u - f / d.slope : 0.5 * (u_lo + u_hi);
    if (!(next > u_lo && next < u_hi)) next = 0.5 * (u_lo + u_hi);
    u = next;
  }
  // Rounding v_p = v_hi + j·u² can add a little distance when j·u² is a few ulps of v_hi; step
  // down until the halves, as the profile will compute them, fit in the length.
  double vp = std::max(v_hi + j * u_lo * u_lo, lo);
  for (int step = 0; step < 64 && vp > lo && peak_distance(vp, v0, v1, a, j) > length_m; ++step) {
    vp = std::nextafter(vp, lo);
  }
  return peak_distance(vp, v0, v1, a, j) > length_m ? lo : vp;
}

}  // namespace stiffpath::motion::detail
