// Total-least-squares line fit (closed-form principal axis of the 2×2 scatter matrix) and line helpers.
#include "stiffpath/evaluation/line_fit.hpp"

#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::evaluation {

LineFit fit_line_tls(std::span<const Point2> points, std::span<const double> weights) {
  if (!weights.empty() && weights.size() != points.size()) {
    throw Error(fmt::format("line fit: {} weights for {} points", weights.size(), points.size()));
  }
  auto weight = [&](std::size_t i) { return weights.empty() ? 1.0 : weights[i]; };
  double sum_w = 0.0;
  Point2 centroid{0.0, 0.0};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double w = weight(i);
    if (!points[i].allFinite() || !std::isfinite(w) || w < 0.0) {
      throw Error(fmt::format("line fit: point {} ({}, {}) with weight {} is not usable", i, points[i].x(),
                              points[i].y(), w));
    }
    sum_w += w;
    centroid += w * points[i];
  }
  if (points.size() < 2 || sum_w <= 0.0) throw Error("line fit: needs at least two points with positive weight");
  centroid /= sum_w;

  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point2 d = points[i] - centroid;
    const double w = weight(i);
    sxx += w * d.x() * d.x();
    syy += w * d.y() * d.y();
    sxy += w * d.x() * d.y();
  }
  // The major axis of [[sxx, sxy], [sxy, syy]] is at angle ½·atan2(2·sxy, sxx − syy).
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  Point2 direction{std::cos(angle), std::sin(angle)};
  const double half_diff = 0.5 * (sxx - syy);
  const double root = std::hypot(half_diff, sxy);
  const double major = 0.5 * (sxx + syy) + root, minor = std::max(0.0, 0.5 * (sxx + syy) - root);
  if (major <= 0.0) throw Error("line fit: all points coincide, the line's direction is undefined");

  Point2 span = points.back() - points.front();
  if (span.norm() <= 1e-9 * std::sqrt(major / sum_w)) span = Point2{1.0, 1e-6};
  if (direction.dot(span) < 0.0) direction = -direction;

  LineFit fit;
  fit.line = Line2{centroid, direction};
  fit.rms_residual_m = std::sqrt(minor / sum_w);
  fit.spread_m = std::sqrt(major / sum_w);
  return fit;
}

std::optional<Point2> intersect(const Line2& a, const Line2& b) {
  const double cross = a.direction.x() * b.direction.y() - a.direction.y() * b.direction.x();
  if (std::abs(cross) < 1e-9) return std::nullopt;
  const Point2 d = b.origin - a.origin;
  const double t = (d.x() * b.direction.y() - d.y() * b.direction.x()) / cross;
  return a.at(t);
}

double angle_between(const Point2& a, const Point2& b) {
  const double cross = a.x() * b.y() - a.y() * b.x();
  return std::atan2(std::abs(cross), a.dot(b));
}

}  // namespace stiffpath::evaluation
