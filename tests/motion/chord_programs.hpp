// Test helper: chord-flattened contours as a CAM post-processor writes them (G-code text, mm).
#pragma once

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <string>

namespace stiffpath::test {

//! `turns` turns of the circle of radius r_mm about (cx_mm, cy_mm), flattened to chords of about
//! chord_mm, coordinates rounded to `decimals` decimals, at feed F (mm/min), under `mode` (e.g.
//! "G64 P0.01"). Starts with a G0 to the first point and the laser on.
inline std::string chord_circle(double cx_mm, double cy_mm, double r_mm, double chord_mm, double feed_mm_min,
                                int decimals = 4, const std::string& mode = "G64 P0.01", int turns = 1) {
  const int n = static_cast<int>(std::ceil(2.0 * std::numbers::pi * r_mm / chord_mm));
  std::string g = fmt::format("G21 G90\n{}\nG0 X{:.{}f} Y{:.{}f}\nM3 S500\nG1 F{}\n", mode, cx_mm + r_mm, decimals,
                              cy_mm, decimals, feed_mm_min);
  for (int k = 1; k <= n * turns; ++k) {
    const double t = 2.0 * std::numbers::pi * k / n;
    g += fmt::format("X{:.{}f} Y{:.{}f}\n", cx_mm + r_mm * std::cos(t), decimals, cy_mm + r_mm * std::sin(t), decimals);
  }
  return g + "M5\nM2\n";
}

//! A straight line from (x0, y) to (x1, y) cut into `pieces` equal collinear moves at feed F (mm/min).
inline std::string split_line(double x0_mm, double x1_mm, double y_mm, int pieces, double feed_mm_min) {
  std::string g = fmt::format("G21 G90\nG64 P0.01\nG0 X{:.6f} Y{:.6f}\nM3 S500\nG1 F{}\n", x0_mm, y_mm, feed_mm_min);
  for (int k = 1; k <= pieces; ++k) g += fmt::format("X{:.6f}\n", x0_mm + (x1_mm - x0_mm) * k / pieces);
  return g + "M5\nM2\n";
}

}  // namespace stiffpath::test
