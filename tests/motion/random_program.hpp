// Test helper: seeded random G-code programs inside the workspace (lines, arcs, tangent arcs, short runs, modes, dwells).
#pragma once

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <random>
#include <string>

namespace stiffpath::test {

//! A random program of about `moves` blocks, in mm, within x ∈ [175, 270], y ∈ [−72, 72].
inline std::string random_program(std::mt19937_64& rng, int moves) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto in_box = [](double x, double y) { return x > 175 && x < 270 && y > -72 && y < 72; };
  double x = 175 + 95 * unit(rng), y = -72 + 144 * unit(rng), heading = 2 * std::numbers::pi * unit(rng);
  std::string g = fmt::format("G21 G90\nG0 X{:.6f} Y{:.6f}\nM3 S800\n", x, y);
  auto feed = [&] { return std::round(600 + 119400 * unit(rng) * unit(rng)); };  // 10 mm/s … 2 m/s
  for (int m = 0; m < moves; ++m) {
    const double pick = unit(rng);
    if (pick < 0.30) {  // a line
      double nx = 0, ny = 0;
      do { nx = 175 + 95 * unit(rng); ny = -72 + 144 * unit(rng); } while (std::hypot(nx - x, ny - y) < 0.01);
      heading = std::atan2(ny - y, nx - x);
      g += fmt::format("G1 X{:.6f} Y{:.6f} F{}\n", nx, ny, feed());
      x = nx, y = ny;
    } else if (pick < 0.45) {  // a run of short segments bending slowly (a polyline from CAM)
      const int n = 3 + static_cast<int>(unit(rng) * 15);
      const double step = 0.05 + unit(rng), bend = (unit(rng) - 0.5) * 0.2;
      g += fmt::format("G1 F{}\n", feed());
      for (int k = 0; k < n; ++k) {
        const double nx = x + step * std::cos(heading + bend), ny = y + step * std::sin(heading + bend);
        if (!in_box(nx, ny)) break;
        heading += bend, x = nx, y = ny;
        g += fmt::format("X{:.6f} Y{:.6f}\n", x, y);
      }
    } else if (pick < 0.65) {  // an arc with I/J about a random centre, or its R form
      const double r = 1 + 29 * unit(rng), phi = 2 * std::numbers::pi * unit(rng);
      const double cx = x - r * std::cos(phi), cy = y - r * std::sin(phi);
      const double sweep = (unit(rng) < 0.5 ? -1 : 1) * (0.1 + 5.5 * unit(rng));
      const double ex = cx + r * std::cos(phi + sweep), ey = cy + r * std::sin(phi + sweep);
      if (!in_box(ex, ey) || !in_box(cx + r, cy) || !in_box(cx - r, cy) || !in_box(cx, cy + r) || !in_box(cx, cy - r)) continue;
      if (std::abs(sweep) < std::numbers::pi && unit(rng) < 0.3) {
        g += fmt::format("G{} X{:.6f} Y{:.6f} R{:.6f} F{}\n", sweep < 0 ? 2 : 3, ex, ey, r, feed());
      } else {
        g += fmt::format("G{} X{:.6f} Y{:.6f} I{:.6f} J{:.6f} F{}\n", sweep < 0 ? 2 : 3, ex, ey, cx - x, cy - y, feed());
      }
      x = ex, y = ey, heading = phi + sweep + (sweep < 0 ? -1 : 1) * std::numbers::pi / 2;
    } else if (pick < 0.78) {  // an arc tangent to the current heading
      const double r = 2 + 20 * unit(rng), side = unit(rng) < 0.5 ? -1.0 : 1.0;
      const double cx = x - side * r * std::sin(heading), cy = y + side * r * std::cos(heading);
      const double sweep = side * (0.2 + 2.5 * unit(rng)), phi = std::atan2(y - cy, x - cx);
      const double ex = cx + r * std::cos(phi + sweep), ey = cy + r * std::sin(phi + sweep);
      if (!in_box(ex, ey) || !in_box(cx + r, cy) || !in_box(cx - r, cy) || !in_box(cx, cy + r) || !in_box(cx, cy - r)) continue;
      g += fmt::format("G{} X{:.6f} Y{:.6f} I{:.6f} J{:.6f} F{}\n", side < 0 ? 2 : 3, ex, ey, cx - x, cy - y, feed());
      x = ex, y = ey, heading += sweep;
    } else if (pick < 0.83) {
      g += fmt::format("G4 P{:.3f}\n", 0.001 + 0.01 * unit(rng));
    } else if (pick < 0.93) {
      g += unit(rng) < 0.5 ? std::string("G61\n") : fmt::format("G64 P{:.4f}\n", 0.002 + 0.05 * unit(rng));
    } else {  // a rapid, laser toggles
      const double nx = 175 + 95 * unit(rng), ny = -72 + 144 * unit(rng);
      if (std::hypot(nx - x, ny - y) < 0.01) continue;
      heading = std::atan2(ny - y, nx - x);
      g += fmt::format("{}G0 X{:.6f} Y{:.6f}\n{}\n", unit(rng) < 0.5 ? "M5\n" : "", nx, ny, unit(rng) < 0.5 ? "M3" : "");
      x = nx, y = ny;
    }
  }
  return g + "M2\n";
}

}  // namespace stiffpath::test
