// Test helper: the calibration proof's held-out jobs (G-code placed over a robot's measured region) and their metric.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/evaluation/segment_distance.hpp"
#include "stiffpath/kinematics/types.hpp"
#include "stiffpath/simulation/simulator.hpp"

namespace stiffpath::test {

using kinematics::Vec2;

// A held-out job: G-code in the robot frame (mm), none of it on the plate.
struct HeldOut {
  std::string name;
  std::string gcode;
};

inline std::string gcode_mm(double v_m) { return fmt::format("{:.4f}", v_m * 1e3); }

// Triangle, star, hatch, circle, diagonal and two off-grid lines, placed by fractions of the robot's measured
// region (so any robot gets its own), at the planner's 5 g, exact stops at corners (G61), 2 m/s feed.
inline std::vector<HeldOut> held_out_jobs(const compliance::GridBounds& r) {
  const double w = r.x_max - r.x_min, h = r.y_max - r.y_min;
  const auto at = [&](double fx, double fy) { return Vec2(r.x_min + fx * w, r.y_min + fy * h); };
  const auto stroke = [&](const std::vector<Vec2>& pts) {
    std::string s = fmt::format("G0 X{} Y{}\nM3 S1000\n", gcode_mm(pts[0].x()), gcode_mm(pts[0].y()));
    for (std::size_t i = 1; i < pts.size(); ++i) s += fmt::format("G1 X{} Y{} F120000\n", gcode_mm(pts[i].x()), gcode_mm(pts[i].y()));
    return s + "M5\n";
  };
  const std::string head = "G21 G90 G17 G94\nG61\n";
  std::vector<HeldOut> jobs;
  jobs.push_back({"triangle", head + stroke({at(0.2, 0.15), at(0.8, 0.2), at(0.45, 0.85), at(0.2, 0.15)}) + "M2\n"});
  {
    std::vector<Vec2> star;
    const Vec2 c = at(0.55, 0.45);
    const double radius = 0.35 * std::min(w, h);
    for (int k = 0; k <= 5; ++k) {
      const double a = std::numbers::pi / 2 + k * 4.0 * std::numbers::pi / 5.0;
      star.push_back(c + radius * Vec2(std::cos(a), std::sin(a)));
    }
    jobs.push_back({"star", head + stroke(star) + "M2\n"});
  }
  {
    std::string hatch = head;
    for (int k = 0; k < 8; ++k) {
      const double fy = 0.2 + 0.085 * k;
      hatch += k % 2 == 0 ? stroke({at(0.15, fy), at(0.85, fy)}) : stroke({at(0.85, fy), at(0.15, fy)});
    }
    jobs.push_back({"hatch", hatch + "M2\n"});
  }
  {
    const Vec2 c = at(0.5, 0.5);
    const double radius = 0.3 * std::min(w, h);
    jobs.push_back({"circle", head + fmt::format("G0 X{} Y{}\nM3 S1000\nG2 X{} Y{} I{} J0 F120000\nM5\nM2\n",
                                                 gcode_mm(c.x() - radius), gcode_mm(c.y()), gcode_mm(c.x() - radius), gcode_mm(c.y()),
                                                 gcode_mm(radius))});
  }
  jobs.push_back({"diagonal", head + stroke({at(0.1, 0.9), at(0.9, 0.1)}) + "M2\n"});
  jobs.push_back({"off-grid", head + stroke({at(0.13, 0.37), at(0.71, 0.62)}) + stroke({at(0.33, 0.08), at(0.62, 0.93)}) +
                                  "M2\n"});
  return jobs;
}

// The largest distance of a marked point from the stroke's commanded polyline (the planned path while the laser was
// on), over every stroke: the max path error.
inline double max_path_error_m(const simulation::Stroke& s) {
  double worst = 0;
  std::size_t k = 0;
  constexpr std::size_t window = 600;  // 0.3 s of samples either side of the sample being marked
  for (std::size_t i = 0; i < s.marked.size(); ++i) {
    while (k + 1 < s.first_mark.size() && s.first_mark[k + 1] <= i) ++k;
    const std::size_t lo = k > window ? k - window : 0, hi = std::min(s.commanded.size(), k + window + 1);
    const std::span<const Vec2> near(s.commanded.data() + lo, hi - lo);
    worst = std::max(worst, evaluation::polyline_distance(s.marked[i], near));
  }
  return worst;
}

}  // namespace stiffpath::test
