// Test helper: an asymmetric five-bar, a known compliance field through its statics, and the table that field gives.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <functional>
#include <string>

#include "cli_runner.hpp"

namespace stiffpath::test {

using V2 = Eigen::Vector2d;
using M2 = Eigen::Matrix2d;

//! The robot of the issue's example (and of examples/robots/asym_5bar.json), written out independently:
//! actuators at (∓40, 0) mm, proximal 120/130 mm, distal 180/170 mm, elbows [+1, −1], 2.2 kg.
struct OwnRobot {
  V2 actuator[2] = {V2(-0.040, 0.0), V2(0.040, 0.0)};
  double proximal[2] = {0.120, 0.130};
  double distal[2] = {0.180, 0.170};
  int elbows[2] = {1, -1};
  double mass_kg = 2.2;

  //! Elbow B_i for the end point c: the proximal circle about A_i meets the distal circle about c on the
  //! side the working mode gives (counter-clockwise of A_i → c for +1).
  [[nodiscard]] V2 elbow(int i, const V2& c) const {
    const V2 d = c - actuator[i];
    const double dist = d.norm(), lp = proximal[i], ld = distal[i];
    const double along = (dist * dist + lp * lp - ld * ld) / (2 * dist);
    const double half = std::sqrt(lp * lp - along * along);
    const V2 unit = d / dist, left(-unit.y(), unit.x());
    return actuator[i] + along * unit + elbows[i] * half * left;
  }
  //! Joint angles θ_i = direction of A_iB_i (rad).
  [[nodiscard]] V2 joints(const V2& c) const {
    V2 q;
    for (int i = 0; i < 2; ++i) {
      const V2 b = elbow(i, c) - actuator[i];
      q[i] = std::atan2(b.y(), b.x());
    }
    return q;
  }
  //! U⁻¹ with U = [u1 u2], u_i the unit vector from B_i to c (the distal links carry F = f1 u1 + f2 u2).
  [[nodiscard]] M2 link_force_map(const V2& c) const {
    M2 U;
    for (int i = 0; i < 2; ++i) U.col(i) = (c - elbow(i, c)).normalized();
    return U.inverse();
  }

  //! The robot file, with its table beside it.
  [[nodiscard]] std::string file(const std::string& table) const {
    return fmt::format(R"({{
  "name": "asym",
  "left_actuator_mm": [-40, 0], "right_actuator_mm": [40, 0],
  "left_proximal_mm": 120, "right_proximal_mm": 130, "left_distal_mm": 180, "right_distal_mm": 170,
  "elbows": [1, -1],
  "moving_mass_kg": 2.2,
  "joints": [
    {{"name": "theta1", "min_deg": 45, "max_deg": 225, "max_velocity_rad_s": 60, "max_acceleration_rad_s2": 8000}},
    {{"name": "theta2", "min_deg": -45, "max_deg": 135, "max_velocity_rad_s": 60, "max_acceleration_rad_s2": 8000}}],
  "compliance": {{"table": "{}"}}
}}
)",
                       table);
  }
};

//! The measured rectangle of the test table and its grid (4 × 3 points).
inline constexpr double kXs[4] = {-0.060, -0.020, 0.020, 0.060};
inline constexpr double kYs[3] = {0.170, 0.210, 0.250};

//! D(p) (m/N), linear over the rectangle x ∈ [−60, 60] mm, y ∈ [170, 250] mm.
inline M2 known_link_compliance(const V2& c) {
  const double X = c.x() / 0.060, Y = (c.y() - 0.210) / 0.040;
  M2 d;
  d << 0.90 + 0.15 * X - 0.10 * Y, 0.12 + 0.04 * X + 0.03 * Y, 0.12 + 0.04 * X + 0.03 * Y, 1.10 - 0.12 * X + 0.18 * Y;
  return d * 1e-6;
}

//! The known field C(p) = U⁻ᵀ D(p) U⁻¹ (m/N): what the physical model can represent exactly.
inline M2 known_compliance(const OwnRobot& r, const V2& c) {
  const M2 Ui = r.link_force_map(c);
  return Ui.transpose() * known_link_compliance(c) * Ui;
}

//! The displacement table `field` gives on the grid: loads +x and −y of 50 … 200 N, minimal columns,
//! displacements to the nanometre.
inline std::string table_of(const std::function<M2(const V2&)>& field) {
  std::string out = "point,x_mm,y_mm,direction,F_N,dx_mm,dy_mm\n";
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 3; ++j) {
      const V2 c(kXs[i], kYs[j]);
      for (const char* dir : {"+x", "-y"}) {
        for (double f : {50.0, 100.0, 150.0, 200.0}) {
          const V2 F = dir[1] == 'x' ? V2(f, 0.0) : V2(0.0, -f);
          const V2 d = field(c) * F;
          out += fmt::format("p{}{},{:.3f},{:.3f},{},{:.1f},{:.6f},{:.6f}\n", i + 1, j + 1, c.x() * 1e3, c.y() * 1e3, dir,
                             f, d.x() * 1e3, d.y() * 1e3);
        }
      }
    }
  }
  return out;
}

}  // namespace stiffpath::test
