// G-code interpreter: the dialect's words, modes and coordinate handling, checked on small hand-written programs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gcode_test_support.hpp"

namespace stiffpath::motion {
namespace {

using test::gcode_error;
using test::read_gcode;
constexpr double pi = std::numbers::pi;

TEST(Gcode, ThesisXMotionInTheRobotFrame) {
  const auto segs = read_gcode("G21 G90\nG0 X172.132 Y0\nM3 S1000\nG1 X272.132 F6000\nM5\nM2\n");
  ASSERT_EQ(segs.size(), 1u);  // the G0 to the start only places the robot (start position unknown)
  const PathSegment& s = segs[0];
  EXPECT_EQ(s.kind, SegmentKind::line);
  EXPECT_DOUBLE_EQ(s.start_m.x(), 0.172132);
  EXPECT_DOUBLE_EQ(s.end_m.x(), 0.272132);
  EXPECT_EQ(s.end_m.y(), 0.0);
  EXPECT_NEAR(s.length_m, 0.1, 1e-15);
  EXPECT_DOUBLE_EQ(s.feed_m_s, 0.1);  // 6000 mm/min
  EXPECT_TRUE(s.laser_on);
  EXPECT_EQ(s.power, 1.0);  // S1000 of the default full scale 1000
  EXPECT_FALSE(s.dynamic_power);
  EXPECT_EQ(s.line, 4);
  EXPECT_FALSE(s.rapid);
  EXPECT_EQ(s.mode, JunctionMode::blend);  // a program that names no mode is blended (the thesis's own file says G61)
  EXPECT_EQ(s.blend_tolerance_m, default_blend_tolerance_m);
}

TEST(Gcode, CompactLowerCaseCommentsLineNumbersAndDelimiters) {
  const auto segs = read_gcode(
      "%\n(header comment)\nN10 g0x1y2\nN20 G1X10Y5F3000 (inline) ; trailing\n  x 12 y -5.\n%\n", {});
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[0].start_m.x(), 0.001);
  EXPECT_DOUBLE_EQ(segs[0].end_m.y(), 0.005);
  EXPECT_EQ(segs[0].line, 4);
  EXPECT_DOUBLE_EQ(segs[1].end_m.x(), 0.012);  // modal G1
  EXPECT_DOUBLE_EQ(segs[1].end_m.y(), -0.005);
  EXPECT_DOUBLE_EQ(segs[1].feed_m_s, 0.05);
}

TEST(Gcode, StartPositionWorkOffsetInchesIncrementalAndG92) {
  GcodeOptions options;
  options.start_position_m = Vec2(0.2, 0.0);
  options.work_offset_m = Vec2(0.2, 0.01);
  const auto segs = read_gcode(
      "G1 X0 Y0 F60\n"        // to the work origin (0.2, 0.01)
      "G20 X1\n"              // one inch right of it
      "G21 G91 X-5 Y-10\n"    // incremental, mm
      "G90 G92 X0 Y0\n"       // here is now (0, 0)
      "G1 X1 Y1\n",
      options);
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_TRUE(segs[0].start_m.isApprox(Vec2(0.2, 0.0)));
  EXPECT_TRUE(segs[0].end_m.isApprox(Vec2(0.2, 0.01)));
  EXPECT_NEAR(segs[1].end_m.x(), 0.2254, 1e-15);
  EXPECT_DOUBLE_EQ(segs[1].feed_m_s, 0.001);  // F60 was given in mm/min; G20 later does not rescale it
  EXPECT_NEAR(segs[2].end_m.x(), 0.2204, 1e-15);
  EXPECT_NEAR(segs[2].end_m.y(), 0.0, 1e-15);
  EXPECT_NEAR(segs[3].end_m.x(), 0.2214, 1e-15);
  EXPECT_NEAR(segs[3].end_m.y(), 0.001, 1e-15);
}

TEST(Gcode, ArcsWithCentreRadiusNegativeRadiusAndFullCircle) {
  const auto segs = read_gcode(
      "G0 X10 Y0\nG1 F600\n"
      "G3 X0 Y10 I-10 J0\n"   // quarter, counter-clockwise about (0, 0)
      "G2 X10 Y0 R10\n"       // back clockwise, short way: centre (0, 0)
      "G2 X0 Y10 R-10\n"      // the long way round: 270° clockwise about (0, 0), not (10, 10)
      "G3 I5\n");             // full circle about (5, 10)
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_EQ(segs[0].kind, SegmentKind::arc);
  EXPECT_NEAR(segs[0].sweep_rad, pi / 2, 1e-12);
  EXPECT_NEAR(segs[0].center_m.norm(), 0.0, 1e-15);
  EXPECT_NEAR(segs[0].length_m, 0.01 * pi / 2, 1e-15);
  EXPECT_NEAR(segs[1].sweep_rad, -pi / 2, 1e-12);
  EXPECT_NEAR(segs[1].center_m.norm(), 0.0, 1e-15);
  EXPECT_NEAR(segs[2].sweep_rad, -1.5 * pi, 1e-12);
  EXPECT_NEAR(segs[2].center_m.norm(), 0.0, 1e-15);
  EXPECT_NEAR(segs[3].sweep_rad, 2 * pi, 1e-15);
  EXPECT_EQ(segs[3].end_m, segs[3].start_m);
  EXPECT_TRUE(segs[3].center_m.isApprox(Vec2(0.005, 0.01), 1e-12));
  // Every arc's geometry ends exactly where it was programmed.
  for (const auto& s : segs) EXPECT_EQ(point_at(s, s.length_m).position_m, s.end_m);
}

TEST(Gcode, ArcEndSlightlyOffTheCircleMovesTheCentreOntoTheBisector) {
  const auto segs = read_gcode("G0 X10 Y0\nG3 X0 Y10.002 I-10 J0 F600\n");  // 2 µm off
  ASSERT_EQ(segs.size(), 1u);
  const PathSegment& a = segs[0];
  EXPECT_NEAR((a.start_m - a.center_m).norm(), (a.end_m - a.center_m).norm(), 1e-15);
  EXPECT_LT(a.center_m.norm(), 2e-6);
  EXPECT_DOUBLE_EQ(a.end_m.y(), 0.010002);
}

TEST(Gcode, DwellPathModesAndLaserStates) {
  const auto segs = read_gcode(
      "G0 X0 Y0\nM3 S500\nG64 P0.02\nG1 X1 F600\nG4 P0.25\nG0 X2\nG61\nS0 G1 X3\nM5 S10 X4\nM4 X5\n");
  ASSERT_EQ(segs.size(), 6u);
  EXPECT_EQ(segs[0].mode, JunctionMode::blend);
  EXPECT_DOUBLE_EQ(segs[0].blend_tolerance_m, 2e-5);
  EXPECT_TRUE(segs[0].laser_on);
  EXPECT_EQ(segs[1].kind, SegmentKind::dwell);
  EXPECT_EQ(segs[1].dwell_s, 0.25);
  EXPECT_TRUE(segs[1].laser_on);             // the laser fires while standing still
  EXPECT_FALSE(segs[2].laser_on);            // G0 never fires
  EXPECT_TRUE(segs[2].rapid);
  EXPECT_EQ(segs[3].mode, JunctionMode::exact_stop);
  EXPECT_FALSE(segs[3].laser_on);            // S0
  EXPECT_FALSE(segs[4].laser_on);            // M5
  EXPECT_TRUE(segs[5].laser_on);             // M4 with S10
  EXPECT_DOUBLE_EQ(segs[5].power, 0.01);  // S10 of 1000
  EXPECT_TRUE(segs[5].dynamic_power);
}

TEST(Gcode, G64WithoutPUsesTheConfiguredTolerance) {
  GcodeOptions options;
  options.default_blend_tolerance_m = 3e-5;
  const auto segs = read_gcode("G0 X0 Y0\nG64 G1 X1 F100\n", options);
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].blend_tolerance_m, 3e-5);
}

TEST(Gcode, ZeroLengthMovesAreDroppedAndReadingStopsAtM2) {
  const auto segs = read_gcode("G0 X1 Y1\nG1 X1 Y1 F100\nG1 X2\nM30\nG1 X3 Z5 (never read)\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].end_m.x(), 0.002);
}

TEST(Gcode, AcceptedNoOpWordsOfCamPreambles) {
  EXPECT_EQ(gcode_error("G17 G21 G40 G49 G54 G80 G90 G94\nM8\nG0 X0 Y0\nM9\n"), "");
}

TEST(Gcode, ErrorsNameFileLineColumnAndWord) {
  EXPECT_EQ(gcode_error("G0 X0 Y0\n  G1 X5 F100 G2 I1\n"),
            "job.gcode:2:14: G2: a second motion word on one line (G1 at column 3)");
  EXPECT_EQ(gcode_error("g17\ng19.1\n"), "job.gcode:2:1: G19.1: only the XY, XZ and YZ planes (G17, G18, G19) are supported");
}

}  // namespace
}  // namespace stiffpath::motion
