// The dialect real CAM programs need: tool length and other planes, vendor M-codes, G64 Q, G92 before the first
// move, G4 P0, dwells before the first move, outputs that are not the laser, and the reader's bounds on a line.
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <sstream>

#include "gcode_test_support.hpp"
#include "stiffpath/motion/line_merge.hpp"
#include "stiffpath/motion/trajectory.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::motion {
namespace {

using test::gcode_error;
using test::read_gcode;

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

TEST(GcodeCam, ToolLengthOffsetsAreIgnoredWithOneWarning) {
  const auto plain = read_gcode("G0 X200 Y0\nG1 X210 F600\n");
  const auto cam = read_gcode("G0 X200 Y0\nG43 Z5 H1\nH2\nG43.1\nG1 X210 F600\nG49\n");
  ASSERT_EQ(cam.size(), plain.size());
  EXPECT_EQ(cam[0].end_m, plain[0].end_m);
  const auto w = warnings_of("G0 X200 Y0\nG43 H1\nG43.1\nG49\n");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].kind, GcodeWarningKind::tool_length_ignored);
  EXPECT_EQ(w[0].count, 2u);  // lines with G43 or H; G49 cancels what was never applied
  EXPECT_EQ(gcode_error("G43 H1\n", strict()), "job.gcode:1:1: G43: tool length compensation is not supported\n"
                                               "job.gcode:1:5: H1: tool length offsets are not supported");
}

TEST(GcodeCam, ArcsInTheXzAndYzPlanesAreTheirXyProjection) {
  // A quarter circle in XZ from (0, z 2) about (2, z 2) to (2, z 0): in XY the line (0,0)-(2,0); in YZ
  // from (2,0) to (2,-2): the line along -Y. Then G17 arcs are arcs again.
  const auto segs = read_gcode("G0 X200 Y0\nG18 G3 X202 Z0 I2 K0 F600\nG19 G2 Y-2 Z2 J-2 K0\nG17 G2 X206 Y-2 I2 J0\n");
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_EQ(segs[0].kind, SegmentKind::line);
  EXPECT_EQ(segs[0].end_m, Vec2(0.202, 0.0));
  EXPECT_DOUBLE_EQ(segs[0].length_m, 0.002);
  EXPECT_EQ(segs[1].kind, SegmentKind::line);
  EXPECT_EQ(segs[1].end_m, Vec2(0.202, -0.002));
  EXPECT_EQ(segs[2].kind, SegmentKind::arc);
  const auto w = warnings_of("G0 X200 Y0\nG18 G3 X202 Z0 I2 K0 F600\nG19 G2 Y-2 Z2 J-2 K0\n");
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[1].kind, GcodeWarningKind::plane_arc_as_line);
  EXPECT_EQ(w[1].count, 2u);
  // K stays refused on arcs in XY, and off arcs anywhere; planes other than these three too.
  EXPECT_EQ(gcode_error("G0 X200 Y0\nG2 X210 I5 K2 F100\n"), "job.gcode:2:12: K2: arcs are in the XY plane; give their centre with I and J");
  EXPECT_EQ(gcode_error("G0 X200 Y0\nG18\nG1 X210 K2 F100\n"),
            "job.gcode:3:9: K2: K belongs to G2/G3 arcs in the XZ (G18) or YZ (G19) plane");
  EXPECT_EQ(gcode_error("G18\n", strict()), "job.gcode:1:1: G18: only the XY plane (G17) is supported");
}

TEST(GcodeCam, VendorMCodesAreIgnoredAsConfiguredWithTheirParameters) {
  const std::string text = "G0 X200 Y0\nM100 P1 Q2\nM17\nM67 E0 Q50\nM52 P1\nG1 X210 F600\nM18\n";
  const auto segs = read_gcode(text);
  ASSERT_EQ(segs.size(), 1u);
  const auto w = warnings_of(text);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].kind, GcodeWarningKind::m_code_ignored);
  EXPECT_EQ(w[0].count, 5u);
  EXPECT_EQ(w[0].message, "M100 and the other configured vendor M-codes are ignored (they do not move the robot)");
  GcodeOptions beep;
  beep.ignored_m_codes = {300};
  EXPECT_EQ(gcode_error("G0 X200 Y0\nM300 S440 P100\n"), "job.gcode:2:1: M300: unsupported M code");
  EXPECT_EQ(gcode_error("G0 X200 Y0\nM300 S440 P100\n", beep), "");
  GcodeOptions none;
  none.ignored_m_codes.clear();
  EXPECT_EQ(gcode_error("M67 E0 Q50\n", none), "job.gcode:1:1: M67: unsupported M code\njob.gcode:1:5: E0: unsupported word");
  EXPECT_EQ(gcode_error("M100\n", strict()), "job.gcode:1:1: M100: unsupported M code");
  // E, L and Q belong to the ignored codes only; the codes the reader runs cannot be ignored.
  EXPECT_EQ(gcode_error("G0 X200 Y0 E5\n"), "job.gcode:1:12: E5: unsupported word");
  EXPECT_EQ(gcode_error("G0 X200 Y0\nG1 X210 Q7 F600\n"), "job.gcode:2:9: Q7: Q belongs to G64 (the tolerance for merging short lines)");
  GcodeOptions own;
  own.ignored_m_codes = {3};
  EXPECT_THROW(validate(own), Error);
}

TEST(GcodeCam, G64QSetsTheMergeToleranceUpToHalfOfP) {
  const auto segs = read_gcode("G0 X200 Y0\nG64 P0.05 Q0.01\nG1 X201 F600\nG64 P0.05\nG1 X202\nG64 P0.05 Q0.1\nG1 X203\n"
                               "G64 P0.05 Q0\nG1 X204\nG61\nG1 X205\n");
  ASSERT_EQ(segs.size(), 5u);
  EXPECT_DOUBLE_EQ(segs[0].merge_tolerance_m, 0.01e-3);
  EXPECT_DOUBLE_EQ(segs[1].merge_tolerance_m, 0.025e-3);  // LinuxCNC's Q defaults to P: half of it here
  EXPECT_DOUBLE_EQ(segs[2].merge_tolerance_m, 0.025e-3);  // so that the blends keep the path within P
  EXPECT_EQ(segs[3].merge_tolerance_m, 0.0);             // Q0: no merging
  EXPECT_EQ(segs[4].merge_tolerance_m, 0.0);             // G61
  EXPECT_EQ(gcode_error("G64 P0.05 Q-1\n"), "job.gcode:1:11: Q-1: blend tolerance must not be negative");
}

TEST(GcodeCam, G92BeforeTheFirstMoveStartsFromTheStartOrTheHome) {
  GcodeOptions home;
  home.home_position_m = Vec2(0.222132, 0.0);
  // The robot stands at its home, which G92 names (0, 0): X10 is 10 mm from home, and takes time.
  auto segs = read_gcode("G92 X0 Y0\nG0 X10 Y0\nG1 X10 Y5 F600\n", home);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_TRUE(segs[0].start_m.isApprox(Vec2(0.222132, 0.0)));
  EXPECT_TRUE(segs[0].end_m.isApprox(Vec2(0.232132, 0.0)));
  EXPECT_TRUE(segs[1].end_m.isApprox(Vec2(0.232132, 0.005)));
  const auto w = warnings_of("G92 X0 Y0\nG0 X10 Y0\n", home);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].kind, GcodeWarningKind::start_at_home);
  EXPECT_EQ(w[0].message, "G92 before the first move: the robot starts at its home position (222.132, 0) mm");
  // A start position comes first, without a warning.
  GcodeOptions start = home;
  start.start_position_m = Vec2(0.2, -0.01);
  segs = read_gcode("G92 X5 Y5\nG1 X10 Y5 F600\n", start);
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_TRUE(segs[0].start_m.isApprox(Vec2(0.2, -0.01)));
  EXPECT_TRUE(segs[0].end_m.isApprox(Vec2(0.205, -0.01)));
  EXPECT_TRUE(warnings_of("G92 X5 Y5\nG1 X10 Y5 F600\n", start).empty());
  // Neither: refused, naming both ways out.
  EXPECT_EQ(gcode_error("G92 X0 Y0\nG0 X10 Y0\n"),
            "job.gcode:1:1: G92: the current position is unknown (give the start or the home position, or move before G92)");
}

TEST(GcodeCam, DwellsBeforeTheFirstMoveTakeTheirTimeWhereTheRobotStands) {
  // pcb2gcode: M3 and a two-second dwell before any XY move. The dwell waits for the first move,
  // which places the robot, and keeps the laser state it was programmed with.
  const auto segs = read_gcode("M3 S1000\nG4 P2\nM5\nG4 P0.5\nG0 X200 Y0\nG1 X210 F600\n");
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_EQ(segs[0].kind, SegmentKind::dwell);
  EXPECT_EQ(segs[0].dwell_s, 2.0);
  EXPECT_TRUE(segs[0].laser_on);
  EXPECT_EQ(segs[0].start_m, Vec2(0.2, 0.0));
  EXPECT_EQ(segs[0].line, 2);
  EXPECT_EQ(segs[1].dwell_s, 0.5);
  EXPECT_FALSE(segs[1].laser_on);
  EXPECT_EQ(segs[2].kind, SegmentKind::line);
  std::istringstream with_dwell("M3 S1000\nG4 P2\nG0 X200 Y0\nG1 X210 F600\n"), alone("G0 X200 Y0\nG1 X210 F600\n");
  EXPECT_NEAR(plan_gcode(with_dwell, "job.gcode").duration_s(), 2.0 + plan_gcode(alone, "a.gcode").duration_s(), 1e-12);
  // A program that never moves dwells at its home when it has one; without, there is nothing to time.
  GcodeOptions home;
  home.home_position_m = Vec2(0.222132, 0.0);
  const auto still = read_gcode("G4 P1\n", home);
  ASSERT_EQ(still.size(), 1u);
  EXPECT_EQ(still[0].start_m, Vec2(0.222132, 0.0));
  EXPECT_TRUE(read_gcode("G4 P1\n").empty());
  // M0 as a dwell before the first move waits too.
  GcodeOptions stop;
  stop.program_stop_dwell_s = 3.0;
  const auto paused = read_gcode("M0\nG0 X200 Y0\n", stop);
  ASSERT_EQ(paused.size(), 1u);
  EXPECT_EQ(paused[0].dwell_s, 3.0);
}

TEST(GcodeCam, G4P0IsAnExactStopThatG64DoesNotBlendThrough) {
  // Two lines at a 90° corner under G64 P0.5 at 50 mm/s: blended through without G4 P0; with it, the
  // path passes through the corner point at rest. Checked on the samples at 2 kHz, independently of the
  // segments: the nearest sample lies within j·T³/6 of the corner (a stop between two samples), and the
  // mean speed of the two samples around it is below 0.3·j·T² (docs/motion.md).
  const std::string corner = "G0 X200 Y0\nM3 S1000\nG64 P0.5\nG1 X220 F3000\n{}G1 X220 Y20\n";
  const auto stream_of = [&](const std::string& between) {
    std::string text = corner;
    text.replace(text.find("{}"), 2, between);
    return text;
  };
  const PlanOptions options;
  const double j = options.limits.max_jerk_m_s3, T = 1.0 / options.rate_hz;
  for (const bool stop : {true, false}) {
    std::istringstream in(stream_of(stop ? "G4 P0\n" : ""));
    TrajectoryStream stream(in, "job.gcode", options);
    std::vector<TrajectorySample> samples;
    while (auto s = stream.next()) samples.push_back(*s);
    std::size_t nearest = 0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      if ((samples[k].position_m - Vec2(0.22, 0.0)).norm() < (samples[nearest].position_m - Vec2(0.22, 0.0)).norm()) nearest = k;
    }
    ASSERT_GT(nearest, 0u);
    ASSERT_LT(nearest + 1, samples.size());
    const double distance = (samples[nearest].position_m - Vec2(0.22, 0.0)).norm();
    const double speed = (samples[nearest + 1].position_m - samples[nearest - 1].position_m).norm() / (2 * T);
    if (stop) {
      EXPECT_LT(distance, j * T * T * T / 6);
      EXPECT_LT(speed, 0.3 * j * T * T);
      EXPECT_TRUE(samples[nearest].laser_on);
    } else {
      EXPECT_GT(speed, 0.3 * j * T * T);  // passed, not stopped at: the corner is blended or passed at its velocity step
    }
  }
  const auto segs = read_gcode(stream_of("G4 P0\n"));
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_EQ(segs[1].kind, SegmentKind::dwell);
  EXPECT_EQ(segs[1].dwell_s, 0.0);
}

TEST(GcodeCam, OutputsThatAreNotTheLaserAreIgnored) {
  GcodeOptions led;
  led.outputs = {{OutputKind::digital, 0, OutputRole::ignored}, {OutputKind::fan, 1, OutputRole::ignored}};
  const std::string text = "G0 X200 Y0\nM62 P0\nG1 X210 F600\nM63 P0\nM62 P1\nG1 X220\nM63 P1\nM106 P1 S255\nG1 X230\nM106 S128\nG1 X240\n";
  const auto as_laser = read_gcode(text);
  const auto configured = read_gcode(text, led);
  ASSERT_EQ(configured.size(), 4u);
  EXPECT_TRUE(as_laser[0].laser_on);    // P0 taken as the laser by default
  EXPECT_FALSE(configured[0].laser_on);  // P0 drives an LED
  EXPECT_TRUE(configured[1].laser_on);   // P1 is still the laser
  EXPECT_FALSE(configured[2].laser_on);  // fan 1 is a fan
  EXPECT_TRUE(configured[3].laser_on);   // fan 0 (M106 without P) drives the laser
  EXPECT_DOUBLE_EQ(configured[3].power, 128.0 / 255.0);
  const auto w = warnings_of(text, led);
  EXPECT_EQ(w[0].kind, GcodeWarningKind::output_ignored);
  EXPECT_EQ(w[0].count, 3u);
  EXPECT_EQ(w[0].first_line, 2);
  EXPECT_EQ(gcode_error("M62 P1.5\n"), "job.gcode:1:5: P1.5: an output number is a whole number, 0 or more");
}

TEST(GcodeCam, OverlongLinesAreRefusedAfterReadingTheLimitAndRefusalsOfOneLineAreCounted) {
  std::string line(max_line_bytes + 10, ' ');
  line[0] = 'G';
  line[1] = '1';
  EXPECT_EQ(gcode_error("G0 X200 Y0\n" + line + "\nG41\n"),
            "job.gcode:2:65537: the line is longer than 65536 bytes, the longest accepted; reading stops here");
  std::string exactly(max_line_bytes, ' ');
  exactly.replace(0, 10, "G0 X200 Y0");
  EXPECT_EQ(gcode_error(exactly + "\r\n"), "");  // 65 536 bytes and its CR LF: accepted
  std::string many;
  for (int k = 0; k < 1000; ++k) many += "G1";
  try {
    read_gcode("G0 X200 Y0\n" + many + "\n");
    FAIL() << "no refusal";
  } catch (const GcodeErrors& e) {
    EXPECT_EQ(e.errors().size(), max_reported_errors);
    EXPECT_EQ(e.omitted(), 999u - max_reported_errors);
  }
}

TEST(GcodeCam, MergedStaircaseStaysWithinItsToleranceBothWays) {
  // A 45° staircase of 0.01 mm steps under G64 P0.02 (ε = 0.01 mm): one merged line, every vertex within
  // ε of it, and its blend tolerance lowered to P − ε.
  std::string g = "G0 X200 Y0\nG64 P0.02\nG1 F6000\n";
  for (int k = 1; k <= 200; ++k) g += fmt::format("G1 X{:.2f} Y{:.2f}\n", 200 + 0.01 * ((k + 1) / 2), 0.01 * (k / 2));
  std::istringstream in(g);
  GcodeReader reader(in, "job.gcode");
  LineMerger merger(reader);
  std::vector<PathSegment> out;
  while (auto s = merger.next()) out.push_back(*s);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].merged);
  EXPECT_TRUE(out[0].end_m.isApprox(Vec2(0.201, 0.001)));
  EXPECT_DOUBLE_EQ(out[0].blend_tolerance_m, 0.01e-3);
  for (int k = 1; k <= 200; ++k) {
    const Vec2 vertex(0.2 + 1e-5 * ((k + 1) / 2), 1e-5 * (k / 2));
    EXPECT_LE(distance_to_segment_m(vertex, out[0].start_m, out[0].end_m), 0.01e-3 * (1 + 1e-9));
  }
  EXPECT_EQ(merger.lines_in(), 200u);
  EXPECT_EQ(merger.merged_out(), 1u);
  // A line longer than 3ε, or a G61 program, is never merged.
  std::istringstream exact("G0 X200 Y0\nG61\nG1 X200.01 F600\nG1 X200.01 Y0.01\nG1 X200.02 Y0.01\n");
  GcodeReader exact_reader(exact, "job.gcode");
  LineMerger exact_merger(exact_reader);
  int n = 0;
  while (exact_merger.next()) ++n;
  EXPECT_EQ(n, 3);
}

}  // namespace
}  // namespace stiffpath::motion
