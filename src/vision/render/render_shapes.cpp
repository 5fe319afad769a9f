// Nominal shapes (line, triangle) and their dense sampling with the decaying wiggle of thesis fig. 4.12.
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/render/render.hpp"

namespace stiffpath::vision {

PathShape line_shape(double length_m) {
  if (!(length_m > 0.0) || !std::isfinite(length_m)) throw Error(fmt::format("line length must be positive, got {} m", length_m));
  return {{{0.0, 0.0}, {length_m, 0.0}}, false};
}

PathShape triangle_shape(double side_m) {
  if (!(side_m > 0.0) || !std::isfinite(side_m)) throw Error(fmt::format("triangle side must be positive, got {} m", side_m));
  // Image coordinates (y down): base at the bottom, apex above; from the bottom-left corner clockwise
  // on screen, the order in which the scan analysis lists sides.
  return {{{0.0, 0.0}, {side_m / 2, -side_m * std::sqrt(3.0) / 2}, {side_m, 0.0}}, true};
}

std::vector<std::vector<Point2>> sample_shape(const PathShape& shape, const Wiggle& wiggle, double step_m) {
  const std::size_t n = shape.vertices.size();
  if (n < 2) throw Error("a path shape needs at least two vertices");
  if (!(step_m > 0.0)) throw Error(fmt::format("sampling step must be positive, got {} m", step_m));
  if (wiggle.amplitude_m != 0.0 && (!(wiggle.wavelength_m > 0.0) || !(wiggle.decay_length_m > 0.0))) {
    throw Error(fmt::format("wiggle wavelength and decay length must be positive, got {} m and {} m", wiggle.wavelength_m,
                            wiggle.decay_length_m));
  }
  for (const auto& v : shape.vertices) {
    if (!v.allFinite()) throw Error("a path shape's vertex is not finite");
  }
  const double step = wiggle.amplitude_m != 0.0 ? std::min(step_m, wiggle.wavelength_m / 100.0) : step_m;
  const std::size_t sides = shape.closed ? n : n - 1;
  double points = 0;  // the budget, before any point is made
  for (std::size_t k = 0; k < sides; ++k) points += std::ceil((shape.vertices[(k + 1) % n] - shape.vertices[k]).norm() / step) + 1;
  if (!(points <= static_cast<double>(kMaxRenderPathPoints))) {
    throw Error(fmt::format("the path would take {:.4g} points at a step of {:.3g} µm{}, above the render budget of {} points", points,
                            step * 1e6, wiggle.amplitude_m != 0.0 ? " (a hundredth of the wiggle's wavelength)" : "", kMaxRenderPathPoints));
  }
  std::vector<std::vector<Point2>> out;
  double s0 = 0.0;  // arc length at the start of the side
  for (std::size_t k = 0; k < sides; ++k) {
    const Point2 a = shape.vertices[k], b = shape.vertices[(k + 1) % n];
    const Point2 d = b - a;
    const double len = d.norm();
    if (!(len > 0.0)) throw Error(fmt::format("side {} of the path shape has zero length", k + 1));
    const Point2 normal{-d.y() / len, d.x() / len};
    const auto count = static_cast<int>(std::ceil(len / step));
    std::vector<Point2> pts;
    pts.reserve(static_cast<std::size_t>(count) + 1);
    for (int i = 0; i <= count; ++i) {
      const double f = static_cast<double>(i) / count, s = s0 + f * len;
      const double offset = wiggle.amplitude_m == 0.0 ? 0.0
                                                      : wiggle.amplitude_m * std::exp(-s / wiggle.decay_length_m) *
                                                            std::sin(2 * std::numbers::pi * s / wiggle.wavelength_m);
      pts.push_back(a + f * d + offset * normal);
    }
    out.push_back(std::move(pts));
    s0 += len;
  }
  return out;
}

}  // namespace stiffpath::vision

namespace stiffpath::vision {

std::vector<Point2> resample_path(const std::vector<Point2>& points, double step_m) {
  if (!(step_m > 0.0)) throw Error(fmt::format("resampling step must be positive, got {} m", step_m));
  double total = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) total += (points[i] - points[i - 1]).norm();
  if (points.size() < 2 || !(total > 0.0)) throw Error("a path needs at least two distinct points");
  if (!std::isfinite(total)) throw Error("a path point is not finite");
  if (!(std::ceil(total / step_m) < static_cast<double>(kMaxRenderPathPoints))) {
    throw Error(fmt::format("the path is {:.0f} mm long: resampled every {:.3g} µm it would take {:.4g} points, above the render budget of {} "
                            "points", total * 1e3, step_m * 1e6, std::ceil(total / step_m) + 1, kMaxRenderPathPoints));
  }
  const auto count = static_cast<std::size_t>(std::ceil(total / step_m));
  const double step = total / static_cast<double>(count);
  std::vector<Point2> out;
  out.reserve(count + 1);
  out.push_back(points.front());
  double s0 = 0.0;  // arc length at points[i - 1]
  std::size_t k = 1;  // next sample: arc length k·step
  for (std::size_t i = 1; i < points.size() && k < count; ++i) {
    const Point2 d = points[i] - points[i - 1];
    const double len = d.norm();
    while (k < count && static_cast<double>(k) * step <= s0 + len) {
      out.push_back(points[i - 1] + d * ((static_cast<double>(k) * step - s0) / len));
      ++k;
    }
    s0 += len;
  }
  out.push_back(points.back());
  return out;
}

}  // namespace stiffpath::vision
