// Per-point least-squares fits of eqs. 4.8–4.11 (four lines per point, plus angular deflections).
#include "stiffpath/compliance/point_fit.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

Mat2 PointFit::compliance() const noexcept {
  Mat2 c;
  c << dx_fx.slope, dx_fy.slope, dy_fx.slope, dy_fy.slope;
  return c;
}

Vec2 PointFit::offset() const noexcept {
  return {dx_fx.intercept + dx_fy.intercept, dy_fx.intercept + dy_fy.intercept};
}

std::optional<Mat2> PointFit::angular_compliance() const noexcept {
  if (!rx_fx || !rx_fy || !ry_fx || !ry_fy) return std::nullopt;
  Mat2 a;
  a << rx_fx->slope, rx_fy->slope, ry_fx->slope, ry_fy->slope;
  return a;
}

std::vector<PointSamples> group_by_point(const measurement::DisplacementTable& table, ForceConvention convention) {
  std::vector<PointSamples> points;
  for (const auto& row : table.rows) {
    auto it = std::find_if(points.begin(), points.end(), [&](const PointSamples& p) { return p.id == row.point; });
    if (it == points.end()) {
      points.push_back({row.point, {row.x_m, row.y_m}, {}});
      it = points.end() - 1;
    } else if ((it->position - Vec2{row.x_m, row.y_m}).norm() > 1e-6) {
      throw Error(SourceLocation{table.source, row.line},
                  fmt::format("point {} is at ({:.3f}, {:.3f}) mm here but at ({:.3f}, {:.3f}) mm earlier", row.point,
                              row.x_m * 1e3, row.y_m * 1e3, it->position.x() * 1e3, it->position.y() * 1e3));
    }
    const double magnitude = convention == ForceConvention::measured ? row.force_N : row.nominal_force_N;
    const Vec2 force{measurement::direction_x(row.direction) * magnitude,
                     measurement::direction_y(row.direction) * magnitude};
    it->samples.push_back({force, row.dx_m, row.dy_m, row.rx_rad, row.ry_rad, row.step, row.line});
  }
  return points;
}

namespace {
// Fits one quantity against one force component, over the samples loaded along that component.
std::optional<LineFit> fit_series(const PointSamples& point, int force_axis,
                                  std::optional<double> PointSample::*quantity) {
  std::vector<double> f, d;
  for (const auto& s : point.samples) {
    const bool along = force_axis == 0 ? s.force_N.y() == 0.0 && s.force_N.x() != 0.0
                                       : s.force_N.x() == 0.0 && s.force_N.y() != 0.0;
    if (!along || !(s.*quantity)) continue;
    f.push_back(s.force_N[force_axis]);
    d.push_back(*(s.*quantity));
  }
  const LineFit fit = fit_line(f, d);
  if (fit.n < 2) return std::nullopt;
  return fit;
}
}  // namespace

PointFit fit_point(const PointSamples& point, const std::string& source) {
  PointFit fit;
  fit.id = point.id;
  fit.position = point.position;
  const auto require = [&](std::optional<LineFit> f, const char* what) {
    if (!f) {
      throw Error(SourceLocation{source},
                  fmt::format("point {}: fewer than two usable load steps for the fit {} (eq. 4.8)", point.id, what));
    }
    return *f;
  };
  fit.dx_fx = require(fit_series(point, 0, &PointSample::dx_m), "dx vs Fx");
  fit.dx_fy = require(fit_series(point, 1, &PointSample::dx_m), "dx vs Fy");
  fit.dy_fx = require(fit_series(point, 0, &PointSample::dy_m), "dy vs Fx");
  fit.dy_fy = require(fit_series(point, 1, &PointSample::dy_m), "dy vs Fy");
  fit.rx_fx = fit_series(point, 0, &PointSample::rx_rad);
  fit.rx_fy = fit_series(point, 1, &PointSample::rx_rad);
  fit.ry_fx = fit_series(point, 0, &PointSample::ry_rad);
  fit.ry_fy = fit_series(point, 1, &PointSample::ry_rad);
  return fit;
}

std::vector<PointFit> fit_points(const measurement::DisplacementTable& table, ForceConvention convention) {
  std::vector<PointFit> fits;
  for (const auto& point : group_by_point(table, convention)) fits.push_back(fit_point(point, table.source));
  if (fits.empty()) throw Error(SourceLocation{table.source}, "no measurement points");
  return fits;
}

}  // namespace stiffpath::compliance
