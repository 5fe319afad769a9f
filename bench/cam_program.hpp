// Benchmark helper: a CAM-like G-code program of many short segments (chord-flattened contours).
#pragma once

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace stiffpath::bench {

//! What a CAM post-processor emits for curved marks: closed contours flattened to chords of
//! 0.1-0.2 mm with 4 decimals, under G64 P0.01, at 100-340 mm/s, with G0 jumps between them. The
//! contours cycle through circles (radius 2-20 mm), ellipses, five-lobed rosettes and 12-tooth gear
//! outlines on a grid inside the thesis's workspace (x 172.132..272.132 mm, y −75..75 mm), until the
//! program has `chords` G1 chords. Deterministic.
inline std::string cam_program(int chords) {
  auto contour = [](int kind, double r, double t) -> std::pair<double, double> {
    if (kind == 0) return {r * std::cos(t), r * std::sin(t)};
    if (kind == 1) return {r * std::cos(t), 0.6 * r * std::sin(t)};
    if (kind == 2) {
      const double rad = r * (1.0 + 0.15 * std::cos(5.0 * t));
      return {rad * std::cos(t), rad * std::sin(t)};
    }
    const double phase = std::fmod(t * 12.0 / (2.0 * std::numbers::pi), 1.0);
    const double s = std::clamp(2.5 - std::abs(phase - 0.5) * 6.0, 0.0, 1.0);
    const double rad = r * (0.9 + 0.1 * (0.5 - 0.5 * std::cos(std::numbers::pi * s)));
    return {rad * std::cos(t), rad * std::sin(t)};
  };
  std::string g = "( CAM-like program: chord-flattened contours )\nG21 G90 G17 G94\nG64 P0.01\nM8\n";
  int written = 0;
  for (int k = 0; written < chords; ++k) {
    const int kind = k % 4;
    const double r = 2.0 + (k * 7) % 19;
    const double cx = 222.132 - 25.0 + 50.0 * ((k * 3) % 11) / 10.0, cy = -45.0 + 90.0 * ((k * 5) % 13) / 12.0;
    const double chord = 0.1 + 0.1 * ((k * 11) % 5) / 4.0;
    const int feed = 6000 + 3000 * (k % 5);
    std::vector<std::pair<double, double>> points;
    for (double t = 0.0; t < 2.0 * std::numbers::pi && written + static_cast<int>(points.size()) < chords;) {
      const auto [x, y] = contour(kind, r, t);
      points.emplace_back(cx + x, cy + y);
      const auto [x2, y2] = contour(kind, r, t + 1e-4);
      t += chord / std::max(std::hypot(x2 - x, y2 - y) / 1e-4, 1e-6);  // about `chord` mm per step
    }
    const auto [x0, y0] = contour(kind, r, 0.0);
    points.emplace_back(cx + x0, cy + y0);
    g += fmt::format("G0 X{:.4f} Y{:.4f}\nM4 S800\nG1 F{}\n", points[0].first, points[0].second, feed);
    for (std::size_t i = 1; i < points.size(); ++i) g += fmt::format("X{:.4f} Y{:.4f}\n", points[i].first, points[i].second);
    g += "M5\n";
    written += static_cast<int>(points.size()) - 1;
  }
  return g + "M9\nG0 X222.1320 Y0.0000\nM2\n";
}

}  // namespace stiffpath::bench
