// Test helper: displacement tables generated from a known compliance field on the thesis's 3 × 5 grid.
#pragma once

#include <functional>
#include <random>
#include <string>

#include "stiffpath/core/units.hpp"
#include "stiffpath/kinematics/types.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::test {

using kinematics::Mat2;
using kinematics::Vec2;

//! Rows for every grid point × {+x, −y} × steps 1–5 with Δ = C(p)·F + offset(p) + N(0, noise²).
inline measurement::DisplacementTable synthetic_table(const std::function<Mat2(const Vec2&)>& compliance,
                                                      const std::function<Vec2(const Vec2&)>& offset,
                                                      double noise_m = 0.0, unsigned seed = 1,
                                                      const std::string& mechanism = "OC") {
  measurement::DisplacementTable table{"synthetic.csv", {}, {}};
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_m > 0 ? noise_m : 1.0);
  const double kgf[5] = {5.0, 9.92, 14.89, 19.83, 24.86};
  const double xs[3] = {0.172132, 0.222132, 0.272132};
  const double ys[5] = {-0.075, -0.0375, 0.0, 0.0375, 0.075};
  int line = 2;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 5; ++j) {
      const Vec2 p{xs[i], ys[j]};
      for (auto dir : {measurement::ForceDirection::plus_x, measurement::ForceDirection::minus_y}) {
        for (int s = 0; s < 5; ++s) {
          measurement::DisplacementRow row;
          row.mechanism = mechanism;
          row.direction = dir;
          row.point = "x" + std::to_string(i + 1) + "y" + std::to_string(j + 1);
          row.x_m = p.x();
          row.y_m = p.y();
          row.step = s + 1;
          row.force_kgf = kgf[s];
          row.force_N = units::kgf_to_N(kgf[s] - 0.11);
          row.nominal_force_N = 50.0 * (s + 1);
          const Vec2 F{measurement::direction_x(dir) * row.force_N, measurement::direction_y(dir) * row.force_N};
          const Vec2 d = compliance(p) * F + offset(p);
          row.dx_m = d.x() + (noise_m > 0 ? noise(rng) : 0.0);
          row.dy_m = d.y() + (noise_m > 0 ? noise(rng) : 0.0);
          row.line = line++;
          table.rows.push_back(row);
        }
      }
    }
  }
  return table;
}

}  // namespace stiffpath::test
