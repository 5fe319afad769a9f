// The test motions of fig. 4.7 placed and scaled inside a robot's measured rectangle, and users' own paths.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "stiffpath/core/error.hpp"
#include "stiffpath/simulation/experiment.hpp"

namespace stiffpath::simulation {

namespace {
using kinematics::Vec2;

// A coordinate in mm with at most three decimals and no trailing zeros: 172.132, -60, 0.
std::string mm(double m) {
  std::string text = fmt::format("{:.3f}", m * 1e3);
  while (text.back() == '0') text.pop_back();
  if (text.back() == '.') text.pop_back();
  return text == "-0" ? "0" : text;
}

// Whether the robot accepts every point of the closed or open polyline, 0.5 mm apart, and 1 mm around
// each (room for the compensation's correction).
bool reachable(const std::vector<Vec2>& vertices, const kinematics::Robot& robot) {
  const kinematics::FiveBar five_bar = robot.five_bar();
  for (std::size_t k = 0; k + 1 < vertices.size(); ++k) {
    const Vec2 a = vertices[k], b = vertices[k + 1];
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.5e-3)));
    for (int i = 0; i <= steps; ++i) {
      const Vec2 p = a + (b - a) * (static_cast<double>(i) / steps);
      for (const Vec2& d : {Vec2(0, 0), Vec2(1e-3, 0), Vec2(-1e-3, 0), Vec2(0, 1e-3), Vec2(0, -1e-3)}) {
        const auto r = five_bar.solve_inverse(p + d);
        if (r.status != kinematics::Reach::ok || !robot.within_limits(r.q)) return false;
      }
    }
  }
  return true;
}

std::string program(const std::vector<Vec2>& v) {
  std::string text = fmt::format("G21 G90 G17 G94\nG61\nG0 X{} Y{}\nM3 S1000\n", mm(v[0].x()), mm(v[0].y()));
  for (std::size_t k = 1; k < v.size(); ++k) {
    text += fmt::format("G1 X{} Y{}{}\n", mm(v[k].x()), mm(v[k].y()), k == 1 ? " F120000" : "");
  }
  return text + "M5\nM2\n";
}
}  // namespace

std::vector<TestMotion> test_motions(const compliance::GridBounds& g, const kinematics::Robot& robot,
                                     const std::vector<double>& grid_x, const std::vector<double>& grid_y) {
  const double w = g.x_max - g.x_min, h = g.y_max - g.y_min;
  const Vec2 c{0.5 * (g.x_min + g.x_max), 0.5 * (g.y_min + g.y_max)};
  std::vector<double> xs = grid_x, ys = grid_y;
  if (xs.size() < 2) xs = {g.x_min, c.x(), g.x_max};
  if (ys.size() < 2) ys = {g.y_min, c.y(), g.y_max};
  std::sort(xs.begin(), xs.end());
  std::sort(ys.begin(), ys.end());
  std::vector<std::pair<std::string, std::vector<Vec2>>> shapes{
      {"x", {{g.x_min, c.y()}, {g.x_max, c.y()}}},
      {"y", {{c.x(), g.y_min}, {c.x(), g.y_max}}},
      {"triangle",
       {{g.x_min + 0.15 * w, g.y_min + 0.1 * h},
        {g.x_max - 0.15 * w, g.y_min + 0.1 * h},
        {c.x(), g.y_max - 0.1 * h},
        {g.x_min + 0.15 * w, g.y_min + 0.1 * h}}},
  };
  for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
    const double x = 0.5 * (xs[k] + xs[k + 1]);
    shapes.push_back({fmt::format("y-mid-{}", k + 1), {{x, g.y_min}, {x, g.y_max}}});
  }
  {
    std::size_t k = 0;  // the row nearest the middle, and the next one up
    for (std::size_t i = 0; i < ys.size(); ++i) {
      if (std::abs(ys[i] - c.y()) < std::abs(ys[k] - c.y())) k = i;
    }
    if (k + 1 >= ys.size()) k = ys.size() - 2;
    const double y = 0.5 * (ys[k] + ys[k + 1]);
    shapes.push_back({"x-mid", {{g.x_min, y}, {g.x_max, y}}});
  }
  {
    // A quarter cell, at most 7.5 % of the width and 5 % of the height (the triangle keeps 15 % and 10 % free).
    const Vec2 shift(std::min(0.25 * (xs[1] - xs[0]), 0.075 * w), std::min(0.25 * (ys[1] - ys[0]), 0.05 * h));
    std::vector<Vec2> v = shapes[2].second;
    for (auto& p : v) p += shift;
    shapes.push_back({"triangle-off", v});
  }
  std::vector<TestMotion> motions;
  for (const auto& [name, vertices] : shapes) {
    bool placed = false;
    for (int tenth = 10; tenth >= 4 && !placed; --tenth) {
      std::vector<Vec2> v;
      for (const Vec2& p : vertices) v.push_back(c + (p - c) * (tenth / 10.0));
      if (!reachable(v, robot)) continue;
      motions.push_back({name, program(v), name.rfind("triangle", 0) == 0 ? 3 : 1, name + "_motion"});
      placed = true;
    }
    if (!placed) {
      throw Error(fmt::format("the {} test motion does not fit robot '{}' even at 40 % of its measured rectangle "
                              "x [{:.3f}, {:.3f}] mm, y [{:.3f}, {:.3f}] mm: give your own paths",
                              name, robot.name, g.x_min * 1e3, g.x_max * 1e3, g.y_min * 1e3, g.y_max * 1e3));
    }
  }
  return motions;
}

const TestMotion& test_motion(const std::vector<TestMotion>& motions, const std::string& name) {
  std::string known;
  for (const auto& m : motions) {
    if (m.name == name) return m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  throw Error(fmt::format("unknown test motion '{}' (known: {})", name, known));
}

TestMotion user_motion(const std::string& file_and_sides) {
  std::string file = file_and_sides;
  int sides = 1;
  if (const auto colon = file_and_sides.rfind(':');
      colon != std::string::npos && colon + 1 < file_and_sides.size() &&
      file_and_sides.find_first_not_of("0123456789", colon + 1) == std::string::npos) {
    file = file_and_sides.substr(0, colon);
    sides = std::stoi(file_and_sides.substr(colon + 1).substr(0, 3));
    if (sides < 1 || sides > 12) throw Error(fmt::format("{}: a path has 1 to 12 sides, got {}", file, sides));
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(SourceLocation{file}, "cannot open G-code file");
  std::ostringstream text;
  text << in.rdbuf();
  return {std::filesystem::path(file).stem().string(), text.str(), sides, file};
}

}  // namespace stiffpath::simulation
