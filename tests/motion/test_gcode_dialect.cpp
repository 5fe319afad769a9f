// The CAM dialect's additions one by one: what each maps to, the warning it leaves, and its refusal in strict mode.
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <sstream>

#include "gcode_test_support.hpp"
#include "stiffpath/motion/trajectory.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::motion {
namespace {

using test::gcode_error;
using test::read_gcode;
constexpr double pi = std::numbers::pi;

// The warnings of a program read to its end.
std::vector<GcodeWarning> warnings_of(const std::string& text, GcodeOptions options = {}) {
  std::istringstream in(text);
  GcodeReader reader(in, "job.gcode", options);
  while (reader.next()) {
  }
  return reader.warnings();
}

GcodeOptions strict() {
  GcodeOptions o;
  o.strict = true;
  return o;
}

TEST(GcodeDialect, ZWordsLeaveTheXyPathAsWithoutThemAndPureZMovesTakeNoTime) {
  const auto with_z = read_gcode("G0 Z5\nG0 X200 Y0 Z5\nG1 Z-1 F100\nG1 X210 Y5 Z-1 F600\nG0 Z5\nG2 X220 Y5 Z-2 I5 J0\n");
  const auto without = read_gcode("G0 X200 Y0\nG1 X210 Y5 F600\nG2 X220 Y5 I5 J0\n");
  ASSERT_EQ(with_z.size(), 2u);
  ASSERT_EQ(without.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(with_z[k].kind, without[k].kind);
    EXPECT_EQ(with_z[k].start_m, without[k].start_m);
    EXPECT_EQ(with_z[k].end_m, without[k].end_m);
    EXPECT_EQ(with_z[k].length_m, without[k].length_m);
    EXPECT_EQ(with_z[k].feed_m_s, without[k].feed_m_s);  // F100 of the plunge stays modal, F600 replaces it
  }
  const auto w = warnings_of("G0 Z5\nG0 X200 Y0\nG1 Z-1 F100\nG1 X210 F600\n");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].kind, GcodeWarningKind::z_ignored);
  EXPECT_EQ(w[0].count, 2u);
  EXPECT_EQ(w[0].first_line, 1);
  EXPECT_EQ(gcode_error("G0 X200 Y0\nG1 X210 Z-1 F100\n", strict()),
            "job.gcode:2:9: Z-1: the robot moves in the XY plane only (no Z axis)");
}

TEST(GcodeDialect, HelixWithOnlyZAndCentreIsTheFullCircle) {
  const auto segs = read_gcode("G0 X200 Y0\nG2 Z-1 I5 J0 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].kind, SegmentKind::arc);
  EXPECT_NEAR(segs[0].sweep_rad, -2 * pi, 1e-15);
  EXPECT_NEAR(segs[0].length_m, 2 * pi * 0.005, 1e-15);
}

TEST(GcodeDialect, G28AndG30GoHomeThroughTheNamedIntermediatePoint) {
  GcodeOptions o;
  o.home_position_m = Vec2(0.222132, 0.0);
  // No axis words: straight home. X and Y: through (230, 10), then home. X only: through X230,
  // then only X goes home, Y stays.
  auto segs = read_gcode("G0 X200 Y-10\nG28\nG0 X200 Y-10\nG30 X230 Y10\nG0 X200 Y-10\nG28 X230\n", o);
  ASSERT_EQ(segs.size(), 7u);
  EXPECT_TRUE(segs[0].end_m.isApprox(Vec2(0.222132, 0.0)));
  EXPECT_TRUE(segs[0].rapid);
  EXPECT_TRUE(segs[2].end_m.isApprox(Vec2(0.230, 0.010)));  // the intermediate point
  EXPECT_TRUE(segs[3].end_m.isApprox(Vec2(0.222132, 0.0)));
  EXPECT_TRUE(segs[5].end_m.isApprox(Vec2(0.230, -0.010)));
  EXPECT_TRUE(segs[6].end_m.isApprox(Vec2(0.222132, -0.010)));  // Y did not go home
  for (const auto& s : segs) EXPECT_FALSE(s.laser_on);
  // G28 G91 X0 Y0 (Fusion's closing line): the intermediate point is where the robot is.
  segs = read_gcode("G0 X200 Y-10\nM3 S500\nG28 G91 X0 Y0\nG90\nG1 X210 F600\n", o);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_TRUE(segs[0].start_m.isApprox(Vec2(0.2, -0.01)));
  EXPECT_TRUE(segs[0].end_m.isApprox(Vec2(0.222132, 0.0)));
  EXPECT_FALSE(segs[0].laser_on);  // rapid
  EXPECT_TRUE(segs[1].start_m.isApprox(Vec2(0.222132, 0.0)));
  EXPECT_TRUE(segs[1].laser_on);
  // As the first move the robot is taken to stand at home already.
  segs = read_gcode("G28\nG1 X230 Y0 F600\n", o);
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_TRUE(segs[0].start_m.isApprox(Vec2(0.222132, 0.0)));
}

TEST(GcodeDialect, G28WithOnlyZNeedsNoHomeAndG28WithXyWithoutHomeIsRefused) {
  EXPECT_EQ(read_gcode("G0 X200 Y0\nG28 G91 Z0.\nG90\nG1 X210 F600\n").size(), 1u);
  EXPECT_EQ(gcode_error("G0 X200 Y0\nG30 X0\n"), "job.gcode:2:1: G30: the robot's home position is not set (home_mm in the robot file)");
  EXPECT_EQ(gcode_error("G0 X200 Y0\nG28\n", strict()), "job.gcode:2:1: G28: homing moves are not supported");
  GcodeOptions o;
  o.home_position_m = Vec2(0.222132, 0.0);
  EXPECT_EQ(gcode_error("G28 X10\n", o), "job.gcode:1:1: G28: the first move must give both X and Y (the start position is unknown)");
}

TEST(GcodeDialect, ToolWordsProgramNumbersAndArcModeAreAcceptedWithoutEffect) {
  const auto plain = read_gcode("G0 X200 Y0\nG1 X210 F600\nG2 X220 I5\n");
  const auto cam = read_gcode("%\nO1001 (plate)\nT1 M6\nG91.1\nG0 X200 Y0\nT2\nM6\nG1 X210 F600\nG2 X220 I5\nM30\n");
  ASSERT_EQ(cam.size(), plain.size());
  for (std::size_t k = 0; k < plain.size(); ++k) EXPECT_EQ(cam[k].end_m, plain[k].end_m);
  const auto w = warnings_of("T1 M6\nG0 X200 Y0\nT2\nM6\n");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].kind, GcodeWarningKind::tool_ignored);
  EXPECT_EQ(w[0].count, 3u);  // lines, not words
  EXPECT_EQ(gcode_error("O1001\n", strict()), "job.gcode:1:1: O1001: program numbers and subroutines are not supported");
  EXPECT_EQ(gcode_error("G90.1\n"), "job.gcode:1:1: G90.1: arc centre modes are not supported (I and J are always relative to the start)");
}

TEST(GcodeDialect, ProgramStopIsARestOrADwellWithTheLaserOff) {
  auto segs = read_gcode("G0 X200 Y0\nM3 S1000\nG64 P1\nG1 X210 F600\nM0\nG1 X220\nM1\n");
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_EQ(segs[1].kind, SegmentKind::dwell);
  EXPECT_EQ(segs[1].dwell_s, 0.0);
  EXPECT_FALSE(segs[1].laser_on);
  EXPECT_TRUE(segs[1].start_m.isApprox(Vec2(0.21, 0.0)));
  EXPECT_EQ(segs[3].kind, SegmentKind::dwell);
  GcodeOptions o;
  o.program_stop_dwell_s = 2.5;
  segs = read_gcode("G0 X200 Y0\nM3 S1000\nG1 X210 F600\nM0\n", o);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[1].dwell_s, 2.5);
  EXPECT_FALSE(segs[1].laser_on);
  EXPECT_EQ(segs[1].power, 0.0);
  EXPECT_EQ(warnings_of("G0 X200 Y0\nM0\nM1\n")[0].count, 2u);

  // The rest is real: two collinear lines blended through at speed stop at an M0 between them.
  const std::string text = "G0 X200 Y0\nG64\nG1 X210 F6000\n{}G1 X220\n";
  std::istringstream through(fmt::format(fmt::runtime(text), "")), stopped(fmt::format(fmt::runtime(text), "M0\n"));
  const Trajectory a = plan_gcode(through, "a.gcode"), b = plan_gcode(stopped, "b.gcode");
  const double t_join_a = a.segments()[0].end_time_s(), t_join_b = b.segments()[0].end_time_s();
  EXPECT_NEAR(a.evaluate(t_join_a).path_speed_m_s, 0.1, 1e-12);
  EXPECT_EQ(b.evaluate(t_join_b).path_speed_m_s, 0.0);
  EXPECT_GT(b.duration_s(), a.duration_s());
}

TEST(GcodeDialect, FanAndDigitalOutputsSwitchTheLaser) {
  const auto segs = read_gcode(
      "G0 X200 Y0\nM106 S128\nG1 X210 F600\nM107\nG1 X220\nM106\nG1 X230\nM62 P0\nS0\nG1 X240\nM63 P0\nG1 X250\n");
  ASSERT_EQ(segs.size(), 5u);
  EXPECT_TRUE(segs[0].laser_on);
  EXPECT_DOUBLE_EQ(segs[0].power, 128.0 / 255.0);
  EXPECT_FALSE(segs[1].laser_on);
  EXPECT_EQ(segs[1].power, 0.0);
  EXPECT_EQ(segs[2].power, 1.0);  // M106 without S: full output
  EXPECT_TRUE(segs[3].laser_on);  // M62: a digital output has no level; the S0 of M3 does not apply
  EXPECT_EQ(segs[3].power, 1.0);
  EXPECT_FALSE(segs[4].laser_on);
  // M106's S is the fan's 0-255 and leaves the laser's S alone.
  const auto mixed = read_gcode("G0 X200 Y0\nS500\nM106 S51\nG1 X210 F600\nM3\nG1 X220\n");
  EXPECT_DOUBLE_EQ(mixed[0].power, 0.2);
  EXPECT_DOUBLE_EQ(mixed[1].power, 0.5);
  const auto w = warnings_of("G0 X200 Y0\nM106\nM107\nM62 P1\nM63 P1\n");
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0].kind, GcodeWarningKind::fan_as_laser);
  EXPECT_EQ(w[0].count, 2u);
  EXPECT_EQ(w[1].kind, GcodeWarningKind::output_as_laser);
  EXPECT_EQ(w[1].first_line, 4);
  EXPECT_EQ(gcode_error("M106\n", strict()), "job.gcode:1:1: M106: unsupported M code");
}

TEST(GcodeDialect, PowerIsSOverItsFullScaleClampedWithAWarning) {
  GcodeOptions o;
  o.s_max = 255;
  const auto segs = read_gcode("G0 X200 Y0\nM3 S51\nG1 X210 F600\nS300\nG1 X220\n", o);
  EXPECT_DOUBLE_EQ(segs[0].power, 0.2);
  EXPECT_EQ(segs[1].power, 1.0);
  const auto w = warnings_of("G0 X200 Y0\nM3 S300\n", o);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].kind, GcodeWarningKind::power_clamped);
  EXPECT_EQ(w[0].message, "S above the full scale 255 is clamped to full power");
  const auto dark = warnings_of("G0 X200 Y0\nM3\nG1 X210 F600\nG0 X200\nG1 X210\n");
  ASSERT_EQ(dark.size(), 1u);
  EXPECT_EQ(dark[0].kind, GcodeWarningKind::laser_without_power);
  EXPECT_EQ(dark[0].count, 2u);  // the feed moves, not the rapid
}

TEST(GcodeDialect, DynamicPowerScalesWithSpeedOverFeedOnEverySample) {
  std::istringstream in("G0 X200 Y0\nM4 S800\nG1 X230 F3000\nG3 X240 Y10 I0 J10\nG4 P0.1\nM3\nG1 X250\n");
  const Trajectory t = plan_gcode(in, "m4.gcode");
  int checked = 0;
  for (double time = 0.0; time <= t.duration_s(); time += 1e-3) {
    const TrajectorySample s = t.evaluate(time);
    const PathSegment& path = t.segments()[s.segment].path;
    ASSERT_TRUE(s.laser_on);
    if (path.line == 7) {
      EXPECT_DOUBLE_EQ(s.power, 0.8);  // M3: constant, even while accelerating
    } else {
      EXPECT_NEAR(s.power, 0.8 * std::min(1.0, s.path_speed_m_s / 0.05), 1e-15) << time;  // 0 in the dwell
    }
    ++checked;
  }
  EXPECT_GT(checked, 500);
  EXPECT_NEAR(t.evaluate(t.segments()[0].start_time_s + 0.5 * t.segments()[0].profile.duration_s).power, 0.8, 1e-12);
}

TEST(GcodeDialect, DwellUnitsAndLongDwellWarning) {
  GcodeOptions ms;
  ms.dwell_p_units = DwellUnits::milliseconds;
  EXPECT_EQ(read_gcode("G0 X200 Y0\nG4 P500\n", ms)[0].dwell_s, 0.5);
  EXPECT_EQ(read_gcode("G0 X200 Y0\nG4 P500\n")[0].dwell_s, 500.0);
  const auto w = warnings_of("G0 X200 Y0\nG4 P500\nG4 P30\nG4 P61\n");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].kind, GcodeWarningKind::long_dwell);
  EXPECT_EQ(w[0].count, 2u);
  EXPECT_EQ(w[0].message, "a dwell of 500 s, over a minute (G4 P is read in seconds)");
  EXPECT_TRUE(warnings_of("G0 X200 Y0\nG4 P59999\n", ms).empty());
  EXPECT_EQ(gcode_error("G0 X200 Y0\nG4 P3601\n"),
            "job.gcode:2:4: P3601: a dwell of 3601 s is longer than the longest block accepted, 3600 s (P is read in seconds)");
}

TEST(GcodeDialect, BlockDeleteRunsBySwitchOffOrIsSkipped) {
  const std::string text = "G0 X200 Y0\n /G1 X210 F600\nG1 X220 F600\n";
  EXPECT_EQ(read_gcode(text).size(), 2u);
  GcodeOptions skip;
  skip.skip_block_delete = true;
  const auto segs = read_gcode(text, skip);
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].length_m, 0.02);
  EXPECT_EQ(warnings_of(text)[0].kind, GcodeWarningKind::block_delete);
  EXPECT_EQ(gcode_error(text, strict()), "job.gcode:2:2: unexpected character '/'");
}

TEST(GcodeDialect, ByteOrderMarkEndOfFileCharacterAndNestedComments) {
  const auto segs = read_gcode("\xEF\xBB\xBFG0 X200 Y0 (a (nested) comment)\r\nG1 X210 F600\r\n\x1AG41 not read\nG41\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(read_gcode("G0 X200 Y0\nG1 X210 F600\x1A G41\n").size(), 1u);  // the text before it on its line counts
  EXPECT_EQ(gcode_error("\xEF\xBB\xBFG0 X200 Y0\n", strict()), "job.gcode:1:1: unexpected non-ASCII character");
  EXPECT_EQ(gcode_error("G0 X200 Y0\n\xEF\xBB\xBFG1 X210 F600\n"), "job.gcode:2:1: unexpected non-ASCII character");
  EXPECT_EQ(gcode_error("(a (nested) comment)\n", strict()), "job.gcode:1:4: comments do not nest: '(' inside a comment");
  EXPECT_EQ(gcode_error("(a (nested comment)\n"), "job.gcode:1:1: comment '(' is not closed on this line");
}

TEST(GcodeDialect, WarningsReachTheCallbackOnceAtTheEndAndNotAfterARefusal) {
  int calls = 0;
  std::size_t kinds = 0;
  GcodeOptions o;
  o.on_warnings = [&](const std::string& file, const std::vector<GcodeWarning>& w) {
    ++calls;
    kinds = w.size();
    EXPECT_EQ(file, "job.gcode");
  };
  read_gcode("G0 X200 Y0 Z1\nT1\n", o);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(kinds, 2u);
  EXPECT_NE(gcode_error("G0 X200 Y0 Z1\nG41\n", o), "");
  EXPECT_EQ(calls, 1);
}

TEST(GcodeDialect, AfterARefusalNothingMoreIsHandedOutAndAllRefusalsComeTogether) {
  std::istringstream in("G0 X200 Y0\nG1 X210 F600\nG41\nG1 X220\nG1 X230 K1\nG19.1\n");
  GcodeReader reader(in, "job.gcode");
  ASSERT_TRUE(reader.next());  // the move before the refused line
  try {
    reader.next();
    FAIL() << "no refusal";
  } catch (const GcodeErrors& e) {
    ASSERT_EQ(e.errors().size(), 3u);
    EXPECT_EQ(e.errors()[1].where().line, 5);
    EXPECT_EQ(e.errors()[1].where().column, 9);
    EXPECT_EQ(e.where().line, 3);
    EXPECT_EQ(e.omitted(), 0u);
  }
  EXPECT_FALSE(reader.next());
}

TEST(GcodeDialect, NumbersBeyondADoubleAndBelowItsSmallest) {
  const std::string tiny = "0." + std::string(400, '0') + "1";
  const auto segs = read_gcode("G0 X200 Y" + tiny + "\nG1 X210 F600\n");
  EXPECT_EQ(segs[0].start_m.y(), 0.0);
  EXPECT_EQ(gcode_error("G0 X200 Y0\nG1 X" + std::string(400, '9') + "\n"),
            "job.gcode:2:4: X" + std::string(24, '9') + "…: number too large");
}

TEST(GcodeDialect, OptionsOutOfRangeAreRefusedByName) {
  GcodeOptions o;
  o.work_offset_m = Vec2(std::nan(""), 0.0);
  EXPECT_THROW(read_gcode("", o), Error);
  o = {};
  o.s_max = 0.0;
  EXPECT_THROW(read_gcode("", o), Error);
  o = {};
  o.program_stop_dwell_s = 1e9;
  EXPECT_THROW(read_gcode("", o), Error);
  o = {};
  o.home_position_m = Vec2(1e12, 0.0);
  try {
    read_gcode("", o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("home_position_m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stiffpath::motion
