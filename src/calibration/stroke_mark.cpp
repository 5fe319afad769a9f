// A plate stroke's commanded geometry: its polyline and its directions at the ends (straight strokes and arcs).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "stiffpath/calibration/plate.hpp"

namespace stiffpath::calibration {

namespace {
Vec2 arc_point(const StrokeMark& m, double turned) {
  const Vec2 r = m.start_m - m.centre_m;
  const double c = std::cos(turned), s = std::sin(turned);
  return m.centre_m + Vec2(c * r.x() - s * r.y(), s * r.x() + c * r.y());
}
// The arc's tangent after turning `turned`, in the direction of travel.
Vec2 arc_tangent(const StrokeMark& m, double turned) {
  const Vec2 radial = (arc_point(m, turned) - m.centre_m).normalized();
  const Vec2 left(-radial.y(), radial.x());
  return m.sweep_rad >= 0.0 ? left : Vec2(-left);
}
}  // namespace

std::vector<Vec2> StrokeMark::polyline_m() const {
  if (kind == StrokeKind::ringing) return {start_m, end_m, tail_end_m};
  if (kind == StrokeKind::timing) return {start_m, end_m};
  constexpr double kStep_rad = 2.0 * std::numbers::pi / 180.0;
  const int n = std::clamp(static_cast<int>(std::ceil(std::abs(sweep_rad) / kStep_rad)), 1, 720);
  std::vector<Vec2> out;
  out.reserve(static_cast<std::size_t>(n) + 1);
  for (int k = 0; k < n; ++k) out.push_back(arc_point(*this, sweep_rad * k / n));
  out.push_back(end_m);
  return out;
}

std::vector<Vec2> StrokeMark::motion_m() const {
  if (kind != StrokeKind::timing || !(run_m > 0.0)) return polyline_m();
  const Vec2 u = (end_m - start_m).normalized();
  return {start_m - run_m * u, start_m, end_m, end_m + run_m * u};
}

Vec2 StrokeMark::start_direction() const {
  return kind == StrokeKind::arc ? arc_tangent(*this, 0.0) : Vec2((end_m - start_m).normalized());
}

Vec2 StrokeMark::end_direction() const {
  if (kind == StrokeKind::arc) return arc_tangent(*this, sweep_rad);
  if (kind == StrokeKind::ringing) return (tail_end_m - end_m).normalized();
  return (end_m - start_m).normalized();
}

}  // namespace stiffpath::calibration
