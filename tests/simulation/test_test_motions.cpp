// Tests of the twin's test motions: the thesis's coordinates on its rectangle, placement in another robot's, users' paths.
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/simulation/experiment.hpp"

namespace stiffpath::simulation {
namespace {

TEST(TestMotions, OnTheThesisRectangleTheyAreFigure47sPaths) {
  const auto motions = test_motions({0.172132, 0.272132, -0.075, 0.075}, kinematics::load_robot("oc-gu"));
  ASSERT_EQ(motions.size(), 3U);
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
