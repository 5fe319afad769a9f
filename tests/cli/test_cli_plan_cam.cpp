// `stiffpath plan` on programs written in the style of five CAM post-processors (tests/data/cam/):
// laser-on path length, duration bounds, laser-on time, power and warnings checked against the geometry by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "stiffpath/core/csv.hpp"

namespace stiffpath::test {
namespace {

namespace fs = std::filesystem;
const fs::path cam = fs::path(STIFFPATH_TEST_DATA_DIR) / "cam";
constexpr double pi = std::numbers::pi;
constexpr double a_mm_s2 = 5 * 9806.65;   // default 5 g
constexpr double ramp_s = 0.005;          // default jerk: a / 5 ms
constexpr double v_max_mm_s = 2000.0;     // default speed limit (G0)
constexpr double period_s = 0.0005;       // 2 kHz

struct Row {
  double t, x, y, vx, vy, power;
  int laser, line;
};

std::vector<Row> read_rows(const fs::path& path) {
  core::CsvReader csv(path.string());
  const std::size_t t = csv.column("t_s"), x = csv.column("x_mm"), y = csv.column("y_mm"), vx = csv.column("vx_mm_s"),
                    vy = csv.column("vy_mm_s"), laser = csv.column("laser"), power = csv.column("power"),
                    line = csv.column("line");
  std::vector<Row> rows;
  while (csv.next()) {
    rows.push_back({csv.number(t), csv.number(x), csv.number(y), csv.number(vx), csv.number(vy), csv.number(power),
                    static_cast<int>(csv.integer(laser)), static_cast<int>(csv.integer(line))});
  }
  return rows;
}

// Length travelled between consecutive samples that both have the laser on (mm).
double laser_on_length_mm(const std::vector<Row>& rows) {
  double length = 0.0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    if (rows[k].laser == 1 && rows[k - 1].laser == 1) length += std::hypot(rows[k].x - rows[k - 1].x, rows[k].y - rows[k - 1].y);
  }
  return length;
}

// A move of the program as the drawing gives it: its length and the speed it cruises at, min(F, v_max).
struct Move {
  double length_mm;
  double speed_mm_s;
  bool laser;
};

// Bounds on a program's time: every move at its cruise speed throughout (lower), every move a
// separate rest-to-rest profile reaching that speed, L/v + v/a + a/j (upper; a junction passed
// without stopping only shortens it).
struct Bounds {
  double lower_s = 0.0, upper_s = 0.0;
};

Bounds bounds(const std::vector<Move>& moves, double dwell_s, bool laser_only) {
  Bounds b{dwell_s, dwell_s};
  for (const Move& m : moves) {
    if (laser_only && !m.laser) continue;
    b.lower_s += m.length_mm / m.speed_mm_s;
    b.upper_s += m.length_mm / m.speed_mm_s + m.speed_mm_s / a_mm_s2 + ramp_s;
  }
  return b;
}

// What a program must give; everything here comes from the program's drawing, not from a run.
struct Expected {
  std::string file;
  std::string flags;
  std::vector<Move> moves;
  double dwell_s = 0.0;           // all dwells
  double laser_dwell_s = 0.0;     // dwells with the laser on
  double laser_length_mm = 0.0;
  double end_x_mm = 0.0, end_y_mm = 0.0;
  // Power by source line: {fraction at the feed, feed (mm/s) for M4, 0 for constant power}.
  std::map<int, std::pair<double, double>> power;
  std::map<std::string, std::pair<int, int>> warnings;  // kind → {count, first line}
  // Corners between two laser-on lines that a blend may round (a program that names no mode is
  // blended within 0.02 mm, G64 P within P): each shortens the path by at most 2·P, whether it is
  // rounded, and how much, is the planner's choice (never slower than a stop).
  int blendable_corners = 0;
  double tolerance_mm = 0.02;
};

void check_program(const Expected& e) {
  SCOPED_TRACE(e.file);
  TempDir dir;
  const CliResult r = run_cli("plan '" + (cam / e.file).string() + "' " + e.flags + " -o job.csv --json", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // with --json the warnings are in the document
  const auto summary = r.json();
  const auto rows = read_rows(dir / "job.csv");
  ASSERT_EQ(rows.size(), summary["samples"].get<std::size_t>());

  const double shortened_mm = 2.0 * e.tolerance_mm * e.blendable_corners;
  EXPECT_LE(laser_on_length_mm(rows), e.laser_length_mm + 0.01);
  EXPECT_GE(laser_on_length_mm(rows), e.laser_length_mm - shortened_mm - 0.01);
  const Bounds all = bounds(e.moves, e.dwell_s, false);
  double slowest_mm_s = v_max_mm_s;
  for (const Move& m : e.moves) slowest_mm_s = std::min(slowest_mm_s, m.speed_mm_s);
  const double duration = summary["duration_s"].get<double>();
  EXPECT_GE(duration, all.lower_s - shortened_mm / slowest_mm_s);
  EXPECT_LE(duration, all.upper_s + period_s);
  const Bounds on = bounds(e.moves, e.laser_dwell_s, true);
  const double laser_on = summary["laser_on_s"].get<double>();
  EXPECT_GE(laser_on, on.lower_s - shortened_mm / slowest_mm_s - 4 * period_s);
  EXPECT_LE(laser_on, on.upper_s + 4 * period_s);
  EXPECT_NEAR(rows.back().x, e.end_x_mm, 1e-6);
  EXPECT_NEAR(rows.back().y, e.end_y_mm, 1e-6);

  double full_power_s = 0.0;
  for (const Row& row : rows) {
    full_power_s += row.power * period_s;
    if (row.laser == 0) {
      ASSERT_EQ(row.power, 0.0) << "t " << row.t;
      continue;
    }
    const auto found = e.power.find(row.line);
    ASSERT_NE(found, e.power.end()) << "laser on at line " << row.line << ", t " << row.t;
    const auto [fraction, feed_mm_s] = found->second;
    const double expected = feed_mm_s > 0.0 ? fraction * std::min(1.0, std::hypot(row.vx, row.vy) / feed_mm_s) : fraction;
    ASSERT_NEAR(row.power, expected, 2e-6) << "line " << row.line << ", t " << row.t;
  }
  EXPECT_NEAR(summary["laser_full_power_s"].get<double>(), full_power_s, 1e-5);

  std::map<std::string, std::pair<int, int>> warnings;
  for (const auto& w : summary["warnings"]) {
    warnings[w["kind"].get<std::string>()] = {w["count"].get<int>(), w["first_line"].get<int>()};
  }
  EXPECT_EQ(warnings, e.warnings);
}

double quarter(double r) { return 0.5 * pi * r; }

TEST(CliPlanCam, FusionStyleLaserProgram) {
  Expected e;
  e.file = "fusion_laser.nc";
  e.flags = "--work-offset-mm 222.132,0";
  e.moves = {{2 * pi * 4, 10, true},  // the hole, F600
             {std::hypot(11.0, 10.0), v_max_mm_s, false},
             {30, 20, true}, {quarter(5), 20, true}, {10, 20, true}, {quarter(5), 20, true},
             {30, 20, true}, {quarter(5), 20, true}, {10, 20, true}, {quarter(5), 20, true}};
  e.laser_length_mm = 2 * pi * 4 + 80 + 2 * pi * 5;
  e.end_x_mm = 222.132 - 15;
  e.end_y_mm = -10;
  e.power = {{14, {1.0, 0}}};
  for (int line = 21; line <= 28; ++line) e.power[line] = {0.75, 0};
  e.warnings = {{"tool_ignored", {1, 8}}, {"z_ignored", {6, 11}}};
  check_program(e);
}

TEST(CliPlanCam, InkscapeGcodetoolsStyleProgram) {
  Expected e;
  e.file = "gcodetools_plate.ngc";
  e.flags = "--work-offset-mm 187.132,-40";
  const double v = 400.0 / 60.0, side = std::hypot(20.0, 30.0);
  e.moves = {{40, v, true}, {side, v, true}, {side, v, true}, {50, v_max_mm_s, false},
             {quarter(10), v, true}, {quarter(10), v, true}, {std::hypot(70.0, 20.0), v_max_mm_s, false}};
  e.laser_length_mm = 40 + 2 * side + 2 * quarter(10);
  e.blendable_corners = 2;  // the triangle's; it names no mode
  e.end_x_mm = 187.132;
  e.end_y_mm = -40;
  for (int line : {16, 17, 18, 30, 31}) e.power[line] = {1.0, 0};
  e.warnings = {{"z_ignored", {11, 12}}};
  check_program(e);
}

TEST(CliPlanCam, LightBurnStyleGrblProgramWithDynamicPower) {
  Expected e;
  e.file = "lightburn_grbl.gcode";
  e.flags = "--work-offset-mm 172.132,-75";
  e.moves = {{40, 20, true}, {30, 20, true}, {40, 20, true}, {30, 20, true},
             {std::hypot(10.0, 15.0), v_max_mm_s, false}, {2 * pi * 10, 50, true},
             {std::hypot(20.0, 25.0), v_max_mm_s, false}};
  e.laser_length_mm = 140 + 2 * pi * 10;
  e.blendable_corners = 3;  // the square's inner corners; it names no mode
  e.end_x_mm = 172.132;
  e.end_y_mm = -75;
  for (int line = 11; line <= 14; ++line) e.power[line] = {0.6, 20.0};  // M4: S600 of 1000 scaled by v / 1200 mm/min
  e.power[17] = {0.3, 50.0};
  check_program(e);
}

TEST(CliPlanCam, MarlinStyleFanLaserSavedOnWindows) {
  Expected e;
  e.file = "marlin_laser.gcode";
  e.flags = "--work-offset-mm 182.132,-40 --dwell-p-units ms";
  e.moves = {{std::hypot(10.0, 10.0), v_max_mm_s, false}, {30, 10, true}, {20, 10, true}, {10, v_max_mm_s, false},
             {20, 10, true}, {20, 10, true}, {std::hypot(70.0, 10.0), v_max_mm_s, false}};
  e.dwell_s = e.laser_dwell_s = 0.5;  // G4 P500 in milliseconds, with M106 on
  e.laser_length_mm = 90;
  e.blendable_corners = 2;  // one in each stroke; it names no mode
  e.end_x_mm = 182.132;
  e.end_y_mm = -40;
  e.power = {{9, {1.0, 0}}, {10, {1.0, 0}}, {11, {1.0, 0}}, {15, {128.0 / 255, 0}}, {16, {128.0 / 255, 0}}};
  e.warnings = {{"fan_as_laser", {5, 5}}};
  check_program(e);
}

TEST(CliPlanCam, LinuxCncStylePlasmaProgramWithOutputsStopAndBlockDelete) {
  Expected e;
  e.file = "linuxcnc_plasma.ngc";
  e.flags = "--work-offset-mm 182.132,-30";
  // G64 P0.05 may round the square's three inner corners (each by a fillet of at most that
  // tolerance, or none where a fillet would be slower than the corner without); the square counts as
  // four moves, each at most a rest-to-rest profile.
  e.moves = {{30, 40, true}, {30, 40, true}, {30, 40, true}, {30, 40, true},
             {std::hypot(100.0, 100.0), v_max_mm_s, false},
             {std::hypot(60.0, 100.0), v_max_mm_s, false}, {20, 40, true}};
  e.dwell_s = 0.5;
  e.laser_length_mm = 120 + 20;
  e.blendable_corners = 3;
  e.tolerance_mm = 0.05;
  e.end_x_mm = 182.132 + 60;
  e.end_y_mm = -30;
  for (int line : {7, 8, 9, 10, 17}) e.power[line] = {1.0, 0};  // M62: a digital output, full power
  e.warnings = {{"output_as_laser", {4, 6}}, {"program_stop", {1, 12}}, {"block_delete", {1, 13}}};
  check_program(e);

  // Skipping the block-delete line drops its two rapids; M1 as a 2 s dwell adds exactly 2 s.
  TempDir dir;
  const std::string job = "plan '" + (cam / e.file).string() + "' --work-offset-mm 182.132,-30 --json";
  const auto base = run_cli(job, dir.path()).json();
  const auto skip = run_cli(job + " --block-delete skip", dir.path()).json();
  const auto dwell = run_cli(job + " --program-stop 2", dir.path()).json();
  const Bounds with_rapids = bounds({{std::hypot(100.0, 100.0), v_max_mm_s, false}, {std::hypot(60.0, 100.0), v_max_mm_s, false}}, 0, false);
  const Bounds without = bounds({{40, v_max_mm_s, false}}, 0, false);
  const double saved = base["duration_s"].get<double>() - skip["duration_s"].get<double>();
  EXPECT_GE(saved, with_rapids.lower_s - without.upper_s - period_s);
  EXPECT_LE(saved, with_rapids.upper_s - without.lower_s + period_s);
  EXPECT_NEAR(dwell["duration_s"].get<double>() - base["duration_s"].get<double>(), 2.0, period_s + 1e-9);
  EXPECT_EQ(skip["warnings"][2]["message"].get<std::string>(), "lines starting with '/' (block delete) are skipped");
}

TEST(CliPlanCam, MarlinDwellReadInSecondsIsWarnedAndLastsFiveHundredSeconds) {
  TempDir dir;
  const std::string job = "plan '" + (cam / "marlin_laser.gcode").string() + "' --work-offset-mm 182.132,-40";
  const CliResult seconds = run_cli(job, dir.path());
  ASSERT_EQ(seconds.exit_code, 0) << seconds.err;
  EXPECT_NE(seconds.err.find("warning: " + (cam / "marlin_laser.gcode").string() +
                             ":9: a dwell of 500 s, over a minute (G4 P is read in seconds)\n"),
            std::string::npos)
      << seconds.err;
  const auto s = run_cli(job + " --json", dir.path()).json();
  const auto ms = run_cli(job + " --json --dwell-p-units ms", dir.path()).json();
  EXPECT_NEAR(s["duration_s"].get<double>() - ms["duration_s"].get<double>(), 499.5, period_s + 1e-9);
  EXPECT_NEAR(s["laser_on_s"].get<double>() - ms["laser_on_s"].get<double>(), 499.5, period_s + 1e-9);
}

TEST(CliPlanCam, StrictRefusesEachCamProgramListingEveryRefusal) {
  TempDir dir;
  const CliResult fusion = run_cli("plan '" + (cam / "fusion_laser.nc").string() + "' --strict -o out.csv", dir.path());
  EXPECT_EQ(fusion.exit_code, 2);
  const std::string f = "error: " + (cam / "fusion_laser.nc").string();
  EXPECT_EQ(fusion.err, f + ":2:1: O1001: program numbers and subroutines are not supported\n" + f +
                            ":5:17: G91.1: arc centre modes are not supported (I and J are always relative to the start)\n" +
                            f + ":8:5: T1: tool selection is not supported\n" + f +
                            ":8:8: M6: tool changes are not supported\n" + f +
                            ":11:8: Z5.: the robot moves in the XY plane only (no Z axis)\n" + f +
                            ":12:8: Z0.: the robot moves in the XY plane only (no Z axis)\n" + f +
                            ":16:8: Z5.: the robot moves in the XY plane only (no Z axis)\n" + f +
                            ":19:8: Z0.: the robot moves in the XY plane only (no Z axis)\n" + f +
                            ":30:9: Z5.: the robot moves in the XY plane only (no Z axis)\n" + f +
                            ":32:6: G28: homing moves are not supported\n" + f +
                            ":32:14: Z0.: the robot moves in the XY plane only (no Z axis)\n");
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
  for (const char* job : {"gcodetools_plate.ngc", "marlin_laser.gcode", "linuxcnc_plasma.ngc"}) {
    const CliResult r = run_cli("plan '" + (cam / job).string() + "' --strict", dir.path());
    EXPECT_EQ(r.exit_code, 2) << job;
    EXPECT_EQ(r.err.rfind("error: " + (cam / job).string() + ":", 0), 0u) << r.err;
  }
  EXPECT_EQ(run_cli("plan '" + (cam / "lightburn_grbl.gcode").string() + "' --strict --work-offset-mm 182.132,-30", dir.path()).exit_code, 0);
}

}  // namespace
}  // namespace stiffpath::test
