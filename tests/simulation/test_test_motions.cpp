// Tests of the twin's test motions: the thesis's coordinates on its rectangle, placement in another robot's, users' paths.
#include <gtest/gtest.h>

#include <sstream>

#include "cli_runner.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/simulation/experiment.hpp"

namespace stiffpath::simulation {
namespace {

TEST(TestMotions, OnTheThesisRectangleTheyAreFigure47sPaths) {
  const auto motions = test_motions({0.172132, 0.272132, -0.075, 0.075}, kinematics::load_robot("oc-gu"));
  ASSERT_GE(motions.size(), 3U);  // then the motions off the grid lines
  EXPECT_EQ(motions[0].gcode, "G21 G90 G17 G94\nG61\nG0 X172.132 Y0\nM3 S1000\nG1 X272.132 Y0 F120000\nM5\nM2\n");
  EXPECT_EQ(motions[1].gcode, "G21 G90 G17 G94\nG61\nG0 X222.132 Y-75\nM3 S1000\nG1 X222.132 Y75 F120000\nM5\nM2\n");
  EXPECT_EQ(motions[2].gcode,
            "G21 G90 G17 G94\nG61\nG0 X187.132 Y-60\nM3 S1000\nG1 X257.132 Y-60 F120000\nG1 X222.132 Y60\n"
            "G1 X187.132 Y-60\nM5\nM2\n");
  EXPECT_EQ(motions[2].sides, 3);
  EXPECT_EQ(motions[1].label, "y_motion");
}

TEST(TestMotions, AMotionThatLeavesTheWorkspaceIsShrunkAboutTheCentre) {
  // The thesis robot on a rectangle reaching to x = 295 mm: the x line cannot go there (the stretched-out
  // margin is at 295 mm, and 1 mm around every point is kept free), so it is shrunk by 10 % steps.
  const auto motions = test_motions({0.195, 0.295, -0.05, 0.05}, kinematics::load_robot("oc-gu"));
  EXPECT_EQ(motions[0].gcode, "G21 G90 G17 G94\nG61\nG0 X200 Y0\nM3 S1000\nG1 X290 Y0 F120000\nM5\nM2\n");
  EXPECT_THROW((void)test_motions({0.25, 0.35, -0.05, 0.05}, kinematics::load_robot("oc-gu")), Error);
  EXPECT_THROW((void)test_motion(motions, "circle"), Error);
}

// Parses "G0/G1 X… Y…" lines of a generated program into its vertices (mm).
std::vector<std::pair<double, double>> vertices(const std::string& gcode) {
  std::vector<std::pair<double, double>> v;
  std::istringstream in(gcode);
  for (std::string line; std::getline(in, line);) {
    const auto x = line.find(" X"), y = line.find(" Y");
    if (x == std::string::npos || y == std::string::npos) continue;
    v.emplace_back(std::stod(line.substr(x + 2)), std::stod(line.substr(y + 2)));
  }
  return v;
}

// Every robot's off-grid motions: no side runs along a grid line (a line of constant x on a grid column, or
// of constant y on a grid row), the y lines sit mid-cell, and everything lies in the measured rectangle.
TEST(TestMotions, OffGridMotionsLieOffTheGridLines) {
  struct Case {
    const char* robot;
    compliance::GridBounds region;
    std::vector<double> xs, ys;
  };
  const std::vector<Case> cases{
      {"oc-gu", {0.172132, 0.272132, -0.075, 0.075}, {0.172132, 0.222132, 0.272132}, {-0.075, -0.0375, 0, 0.0375, 0.075}},
      {STIFFPATH_SOURCE_DIR "/examples/robots/asym_5bar.json", {-0.06, 0.06, 0.17, 0.25}, {-0.06, -0.02, 0.02, 0.06}, {0.17, 0.21, 0.25}}};
  for (const auto& c : cases) {
    const auto robot = kinematics::load_robot(c.robot);
    const auto motions = test_motions(c.region, robot, c.xs, c.ys);
    int y_mid = 0;
    for (const auto& m : motions) {
      if (m.name == "x" || m.name == "y" || m.name == "triangle") continue;
      const auto v = vertices(m.gcode);
      ASSERT_GE(v.size(), 2U) << m.name;
      if (m.name.rfind("y-mid-", 0) == 0) {
        ++y_mid;
        const std::size_t k = std::stoul(m.name.substr(6));
        EXPECT_NEAR(v[0].first, 500.0 * (c.xs[k - 1] + c.xs[k]), 1e-3) << m.name;  // mid-cell
      }
      for (std::size_t i = 0; i + 1 < v.size(); ++i) {
        const auto [x0, y0] = v[i];
        const auto [x1, y1] = v[i + 1];
        for (double gx : c.xs) EXPECT_FALSE(std::abs(x0 - x1) < 1e-9 && std::abs(x0 - gx * 1e3) < 1.0) << m.name;
        for (double gy : c.ys) EXPECT_FALSE(std::abs(y0 - y1) < 1e-9 && std::abs(y0 - gy * 1e3) < 1.0) << m.name;
        for (double x : {x0, x1}) {
          EXPECT_GE(x, c.region.x_min * 1e3 - 1e-6);
          EXPECT_LE(x, c.region.x_max * 1e3 + 1e-6);
        }
        for (double y : {y0, y1}) {
          EXPECT_GE(y, c.region.y_min * 1e3 - 1e-6);
          EXPECT_LE(y, c.region.y_max * 1e3 + 1e-6);
        }
      }
    }
    EXPECT_EQ(y_mid, static_cast<int>(c.xs.size()) - 1) << c.robot;
    EXPECT_NO_THROW((void)test_motion(motions, "x-mid"));
    EXPECT_EQ(test_motion(motions, "triangle-off").sides, 3);
  }
  // The thesis's mid-cell lines: x = 197.132 and 247.132 mm.
  const auto thesis = test_motions({0.172132, 0.272132, -0.075, 0.075}, kinematics::load_robot("oc-gu"),
                                   {0.172132, 0.222132, 0.272132}, {-0.075, -0.0375, 0, 0.0375, 0.075});
  EXPECT_EQ(vertices(test_motion(thesis, "y-mid-2").gcode).front().first, 247.132);
  EXPECT_EQ(vertices(test_motion(thesis, "x-mid").gcode).front().second, 18.75);
}

TEST(TestMotions, UsersPathsAreReadWithTheirSides) {
  test::TempDir dir;
  test::write_text(dir / "square.gcode", "G0 X200 Y0\n");
  const TestMotion m = user_motion((dir / "square.gcode").string() + ":4");
  EXPECT_EQ(m.name, "square");
  EXPECT_EQ(m.sides, 4);
  EXPECT_EQ(m.gcode, "G0 X200 Y0\n");
  EXPECT_EQ(user_motion((dir / "square.gcode").string()).sides, 1);
  EXPECT_THROW((void)user_motion((dir / "square.gcode").string() + ":40"), Error);
  EXPECT_THROW((void)user_motion((dir / "none.gcode").string()), Error);
}

}  // namespace
}  // namespace stiffpath::simulation
