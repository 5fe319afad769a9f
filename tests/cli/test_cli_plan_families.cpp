// `stiffpath plan` on programs in the style of more CAM generators (tests/data/cam/): each family's dialect
// (G43/H, G18/G19 arcs, vendor M-codes, G64 Q, G92 first, G4 P0, dwells before the first move, outputs
// that are not the laser), checked against the drawing each program was written from.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "stiffpath/core/csv.hpp"

namespace stiffpath::test {
namespace {

namespace fs = std::filesystem;
const fs::path cam = fs::path(STIFFPATH_TEST_DATA_DIR) / "cam";
constexpr double pi = std::numbers::pi;
constexpr double period_s = 0.0005;

struct Row {
  double t, x, y, vx, vy;
  int laser, line;
};

std::vector<Row> read_rows(const fs::path& path) {
  core::CsvReader csv(path.string());
  const std::size_t t = csv.column("t_s"), x = csv.column("x_mm"), y = csv.column("y_mm"), vx = csv.column("vx_mm_s"),
                    vy = csv.column("vy_mm_s"), laser = csv.column("laser"), line = csv.column("line");
  std::vector<Row> rows;
  while (csv.next()) {
    rows.push_back({csv.number(t), csv.number(x), csv.number(y), csv.number(vx), csv.number(vy),
                    static_cast<int>(csv.integer(laser)), static_cast<int>(csv.integer(line))});
  }
  return rows;
}

// A drawing: polylines in the robot frame (mm); arcs are given as dense polylines (0.001 mm sagitta at most).
using Polyline = std::vector<std::array<double, 2>>;

double distance_to(const Polyline& p, double x, double y) {
  double best = INFINITY;
  for (std::size_t k = 0; k + 1 < p.size(); ++k) {
    const double ax = p[k][0], ay = p[k][1], bx = p[k + 1][0], by = p[k + 1][1];
    const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    const double s = l2 > 0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / l2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(x - ax - s * dx, y - ay - s * dy));
  }
  return best;
}

double length_of(const Polyline& p) {
  double l = 0.0;
  for (std::size_t k = 0; k + 1 < p.size(); ++k) l += std::hypot(p[k + 1][0] - p[k][0], p[k + 1][1] - p[k][1]);
  return l;
}

// An arc about (cx, cy) of radius r from angle a0 to a1 (rad), as a polyline of 2000 points.
Polyline arc(double cx, double cy, double r, double a0, double a1) {
  Polyline p;
  for (int k = 0; k <= 2000; ++k) {
    const double a = a0 + (a1 - a0) * k / 2000;
    p.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
  }
  return p;
}

void append(Polyline& to, const Polyline& more) { to.insert(to.end(), more.begin(), more.end()); }

// Every laser-on sample lies within `tolerance_mm` of the drawing; returns the largest distance.
double laser_deviation_mm(const std::vector<Row>& rows, const std::vector<Polyline>& drawing) {
  double worst = 0.0;
  for (const Row& r : rows) {
    if (r.laser == 0) continue;
    double d = INFINITY;
    for (const Polyline& p : drawing) d = std::min(d, distance_to(p, r.x, r.y));
    worst = std::max(worst, d);
  }
  return worst;
}

double laser_on_length_mm(const std::vector<Row>& rows) {
  double length = 0.0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    if (rows[k].laser == 1 && rows[k - 1].laser == 1) length += std::hypot(rows[k].x - rows[k - 1].x, rows[k].y - rows[k - 1].y);
  }
  return length;
}

std::map<std::string, std::pair<int, int>> warnings_of(const nlohmann::json& summary) {
  std::map<std::string, std::pair<int, int>> out;
  for (const auto& w : summary["warnings"]) out[w["kind"].get<std::string>()] = {w["count"].get<int>(), w["first_line"].get<int>()};
  return out;
}

struct Planned {
  nlohmann::json summary;
  std::vector<Row> rows;
};

Planned plan(const std::string& file, const std::string& flags, const TempDir& dir) {
  const CliResult r = run_cli("plan '" + (cam / file).string() + "' " + flags + " -o job.csv --json", dir.path());
  EXPECT_EQ(r.exit_code, 0) << file << ": " << r.err;
  EXPECT_EQ(r.err, "");
  if (r.exit_code != 0) return {};
  Planned p{r.json(), read_rows(dir.path() / "job.csv")};
  EXPECT_EQ(p.rows.size(), p.summary["samples"].get<std::size_t>());
  return p;
}

// The saving of a fillet of tolerance P at a 90° corner (mm): 2d − r·π/2 with r = P·cos45°/(1 − cos45°).
double fillet_saving_mm(double p_mm) {
  const double r = p_mm * std::cos(pi / 4) / (1 - std::cos(pi / 4));
  return 2 * r - r * pi / 2;
}

TEST(CliPlanFamilies, FusionMillingPostWithToolLengthPlaneArcsVendorCodesAndAnLedOutput) {
  // The bracket: a ramp arc in XZ (its XY projection: the line (0,0)-(2,0)), a 20 x 10 rectangle, a
  // lead-out arc in YZ ((0,0)-(0,-2)), all at the default blend tolerance, 0.02 mm.
  TempDir dir;
  const double ox = 212.132, oy = -5.0;
  const std::string flags = "--work-offset-mm 212.132,-5 ";
  const Planned led = plan("fusion_mill_laser.nc", flags + "--outputs P0=ignore", dir);
  const Planned lit = plan("fusion_mill_laser.nc", flags, dir);  // P0 taken as the laser (the default)
  ASSERT_FALSE(led.rows.empty());
  ASSERT_FALSE(lit.rows.empty());
  const Polyline drawn{{ox + 0, oy}, {ox + 20, oy}, {ox + 20, oy + 10}, {ox + 0, oy + 10}, {ox + 0, oy + 0}, {ox, oy - 2}};
  EXPECT_LE(laser_deviation_mm(led.rows, {drawn}), 0.02 + 1e-6);
  const double drawn_length = length_of(drawn);
  EXPECT_LE(laser_on_length_mm(led.rows), drawn_length + 0.01);
  EXPECT_GE(laser_on_length_mm(led.rows), drawn_length - 3 * fillet_saving_mm(0.02) - 0.01);
  const std::map<std::string, std::pair<int, int>> expected{
      {"z_ignored", {5, 8}},       {"tool_ignored", {1, 10}},       {"m_code_ignored", {1, 12}},
      {"output_ignored", {2, 27}}, {"tool_length_ignored", {1, 14}}, {"plane_arc_as_line", {2, 17}}};
  EXPECT_EQ(warnings_of(led.summary), expected);
  // The parking move after M5 and M62 P0 (line 28) fires only if P0 is the laser.
  bool parked_dark = true, parked_lit = false;
  for (const Row& r : led.rows) parked_dark = parked_dark && !(r.line == 28 && r.laser == 1);
  for (const Row& r : lit.rows) parked_lit = parked_lit || (r.line == 28 && r.laser == 1);
  EXPECT_TRUE(parked_dark);
  EXPECT_TRUE(parked_lit);
  EXPECT_EQ(warnings_of(lit.summary).count("output_ignored"), 0u);
  EXPECT_EQ(warnings_of(lit.summary).at("output_as_laser"), std::make_pair(2, 27));
}

TEST(CliPlanFamilies, CamBamProfileWithABareG64UsesTheDefaultTolerance) {
  TempDir dir;
  const double ox = 192.132, oy = -10.0;
  const Planned p = plan("cambam_profile.nc", "--work-offset-mm 192.132,-10", dir);
  ASSERT_FALSE(p.rows.empty());
  Polyline drawn{{ox, oy}, {ox + 30, oy}};
  append(drawn, arc(ox + 30, oy + 5, 5, -pi / 2, 0));
  append(drawn, arc(ox + 30, oy + 15, 5, 0, pi / 2));
  append(drawn, {{ox, oy + 20}, {ox, oy}});
  EXPECT_LE(laser_deviation_mm(p.rows, {drawn}), 0.02 + 1e-6);
  EXPECT_NEAR(laser_on_length_mm(p.rows), length_of(drawn), fillet_saving_mm(0.02) + 0.01);
  const std::map<std::string, std::pair<int, int>> expected{{"z_ignored", {4, 4}}, {"tool_ignored", {1, 6}}};
  EXPECT_EQ(warnings_of(p.summary), expected);
}

TEST(CliPlanFamilies, PyCamG64QMergesTheJitterOfAStraightEdgeWithinP) {
  // A hexagon whose first edge carries ten 0.02 mm steps wiggling by 3 µm: Q0.01 merges them into the
  // edge (fewer segments than with Q0), and the path stays within P = 0.05 mm of the drawing.
  TempDir dir;
  const double ox = 212.132, oy = -8.0;
  const std::string flags = "--work-offset-mm 212.132,-8";
  const Planned merged = plan("pycam_contour.ngc", flags, dir);
  ASSERT_FALSE(merged.rows.empty());
  const Polyline hexagon{{ox, oy},           {ox + 20, oy},           {ox + 25, oy + 8.6603}, {ox + 20, oy + 17.3205},
                         {ox + 10, oy + 17.3205}, {ox + 5, oy + 8.6603}, {ox, oy}};
  EXPECT_LE(laser_deviation_mm(merged.rows, {hexagon}), 0.05 + 1e-6);
  // The same program with Q0: no merging.
  std::ifstream in(cam / "pycam_contour.ngc");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  text.replace(text.find("Q0.01"), 5, "Q0");
  std::ofstream(dir.path() / "q0.ngc") << text;
  const CliResult q0 = run_cli("plan q0.ngc " + flags + " --json", dir.path());
  ASSERT_EQ(q0.exit_code, 0) << q0.err;
  EXPECT_LT(merged.summary["segments"].get<int>() + 5, q0.json()["segments"].get<int>());
  const std::map<std::string, std::pair<int, int>> expected{{"z_ignored", {3, 11}}, {"tool_ignored", {1, 9}}};
  EXPECT_EQ(warnings_of(merged.summary), expected);
}

TEST(CliPlanFamilies, Pcb2gcodeDwellBeforeTheFirstMoveTakesItsTime) {
  // G04 P2 comes before any XY move: the robot stands (laser on: M3) for 2 s where the first move puts it.
  // Pads of 0.6 mm radius in 0.1 mm chords at F600: the account of lost time names their lines.
  TempDir dir;
  const Planned p = plan("pcb2gcode_isolation.ngc", "--work-offset-mm 212.132,0", dir);
  ASSERT_FALSE(p.rows.empty());
  // Time at the programmed feeds: 2 s of dwell, two 38-chord polygons at 10 mm/s, two rapids at 2 m/s.
  const double chord = 2 * 0.6 * std::sin(pi / 38);
  const double programmed = 2.0 + 2 * 38 * chord / 10.0 + 5.0 / 2000.0;
  const auto& slow = p.summary["slowdowns"];
  EXPECT_NEAR(slow["programmed_time_s"].get<double>(), programmed, 1e-4);  // the file's 5 decimals
  EXPECT_GE(p.summary["duration_s"].get<double>(), 2.0 + 2 * 38 * chord / 10.0 - 1e-9);
  // The first 2 s: at rest at the first pad's start, laser on.
  for (const Row& r : p.rows) {
    if (r.t > 2.0 - 1e-9) break;
    EXPECT_NEAR(r.x, 212.132 + 0.6, 1e-6);
    EXPECT_NEAR(r.y, 0.0, 1e-6);
    EXPECT_EQ(r.vx, 0.0);
    EXPECT_EQ(r.laser, 1);
  }
  EXPECT_GE(p.summary["laser_on_s"].get<double>(), 2.0);
  ASSERT_GE(slow["stretches"].size(), 1u);
  const auto& worst = slow["stretches"][0];
  EXPECT_GE(worst["first_line"].get<int>(), 12);
  EXPECT_LE(worst["last_line"].get<int>(), 100);
  EXPECT_GT(worst["lost_s"].get<double>(), 0.0);
  double by_limit = 0.0;
  for (const auto& [limit, seconds] : slow["lost_s"].items()) by_limit += seconds.get<double>();
  // planned = programmed + lost − what the blends' shorter path saves (all of it to the end's sample).
  EXPECT_NEAR(by_limit - slow["shortcut_s"].get<double>(),
              p.summary["duration_s"].get<double>() - slow["programmed_time_s"].get<double>(), period_s);
}

TEST(CliPlanFamilies, SheetCamG4P0IsAnExactStopUnderG64) {
  // Independent check on the sampled path: the corner after G04 P0 is passed through exactly, at rest
  // (the samples' own finite-difference speed there is below what a jerk ramp reaches in one period);
  // without G04 P0 the same corner is rounded by P = 0.1 mm or passed without a fillet, not stopped at.
  TempDir dir;
  const std::string flags = "--work-offset-mm 202.132,-10";
  const Planned p = plan("sheetcam_plasma.tap", flags, dir);
  ASSERT_FALSE(p.rows.empty());
  const double cx = 242.132, cy = 10.0;  // (40, 20) in the program
  std::size_t nearest = 0;
  for (std::size_t k = 0; k < p.rows.size(); ++k) {
    if (std::hypot(p.rows[k].x - cx, p.rows[k].y - cy) < std::hypot(p.rows[nearest].x - cx, p.rows[nearest].y - cy)) nearest = k;
  }
  // From rest at an instant between two samples, the path moves at most j·t³/6 in t: the nearest
  // sample lies within j·T³/6 (T = one period) of the corner, and the two samples around it (within
  // 1.5 T and 0.5 T of the stop) span at most j·((1.5T)³ + (0.5T)³)/6 in 2T, a mean speed of 0.3·j·T².
  const double j = 5 * 9806.65 / 0.005;  // mm/s^3, the default jerk
  const double T = period_s;
  EXPECT_LT(std::hypot(p.rows[nearest].x - cx, p.rows[nearest].y - cy), j * T * T * T / 6);
  ASSERT_GT(nearest, 0u);
  ASSERT_LT(nearest + 1, p.rows.size());
  const auto& a = p.rows[nearest - 1];
  const auto& b = p.rows[nearest + 1];
  EXPECT_LT(std::hypot(b.x - a.x, b.y - a.y) / (b.t - a.t), 0.3 * j * T * T);
  std::ifstream in(cam / "sheetcam_plasma.tap");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  text.replace(text.find("G04 P0 "), 6, "(    )");
  std::ofstream(dir.path() / "round.tap") << text;
  const CliResult round = run_cli("plan round.tap " + flags + " -o round.csv", dir.path());
  ASSERT_EQ(round.exit_code, 0) << round.err;
  double closest = INFINITY, slowest = INFINITY;
  const auto rows = read_rows(dir.path() / "round.csv");
  for (std::size_t k = 1; k + 1 < rows.size(); ++k) {
    const double d = std::hypot(rows[k].x - cx, rows[k].y - cy);
    if (d < 0.5) slowest = std::min(slowest, std::hypot(rows[k].vx, rows[k].vy));
    closest = std::min(closest, d);
  }
  EXPECT_GT(slowest, 1.0);  // mm/s: not a stop (the least a corner is passed at: j·τ²/(2·sin 45°) = 1.7 mm/s)
  EXPECT_LE(closest, 0.1 + 0.002);  // P, and the path between two samples near the corner
}

TEST(CliPlanFamilies, LasertoolsG92FirstStartsAtHomeAndIgnoresTheStepperCodes) {
  // G92 X0 Y0 before any move: the robot stands at its home (oc-gu: 222.132, 0), which becomes (0, 0).
  TempDir dir;
  const Planned p = plan("lasertools_marlin.gcode", "", dir);
  ASSERT_FALSE(p.rows.empty());
  EXPECT_NEAR(p.rows.front().x, 222.132, 1e-9);
  EXPECT_NEAR(p.rows.front().y, 0.0, 1e-9);
  EXPECT_NEAR(p.rows.back().x, 222.132, 1e-6);
  EXPECT_NEAR(p.rows.back().y, 0.0, 1e-6);
  const Polyline square{{232.132, 0}, {242.132, 0}, {242.132, 10}, {232.132, 10}, {232.132, 0}};
  EXPECT_LE(laser_deviation_mm(p.rows, {square}), 0.02 + 1e-6);
  // G4 P0 before the laser fires: the mark starts at (10, 0) exactly, at rest.
  for (std::size_t k = 0; k < p.rows.size(); ++k) {
    if (p.rows[k].laser == 1) {
      EXPECT_NEAR(p.rows[k].x, 232.132, 1e-3);  // at rest there: within j·T³/6 = 0.2 µm of it
      EXPECT_NEAR(p.rows[k].y, 0.0, 1e-9);
      break;
    }
  }
  const std::map<std::string, std::pair<int, int>> expected{
      {"m_code_ignored", {2, 3}}, {"start_at_home", {1, 4}}, {"fan_as_laser", {3, 7}}};
  EXPECT_EQ(warnings_of(p.summary), expected);
  // Without a home (a robot file that has none) G92 first is refused, naming both ways out.
  const CliResult refused =
      run_cli("plan '" + (cam / "lasertools_marlin.gcode").string() + "' --robot '" +
                  (fs::path(STIFFPATH_TEST_DATA_DIR) / "robots" / "oc-gu-no-home.json").string() + "'",
              dir.path());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find(":4:1: G92: the current position is unknown (give the start or the home position"),
            std::string::npos)
      << refused.err;
  // With a start position the robot starts there instead.
  const CliResult started = run_cli("plan '" + (cam / "lasertools_marlin.gcode").string() + "' --start-mm 200,-20 -o s.csv",
                                    dir.path());
  ASSERT_EQ(started.exit_code, 0) << started.err;
  const auto rows = read_rows(dir.path() / "s.csv");
  EXPECT_NEAR(rows.front().x, 200.0, 1e-9);
  EXPECT_NEAR(rows.back().y, -20.0, 1e-6);
}

TEST(CliPlanFamilies, VectricJscutAndSvg2gcodePrograms) {
  TempDir dir;
  // Vectric (GRBL laser): a 30 x 20 plate with corners of radius 5, tangent all round.
  const Planned v = plan("vectric_laser.gcode", "--work-offset-mm 202.132,-10", dir);
  ASSERT_FALSE(v.rows.empty());
  EXPECT_NEAR(laser_on_length_mm(v.rows), 60 + 10 * pi, 0.01);
  EXPECT_EQ(warnings_of(v.summary), (std::map<std::string, std::pair<int, int>>{{"tool_ignored", {1, 1}}}));
  // jscut: G1 everywhere, no laser; 10 x 10 square at 1016 mm/min.
  const Planned j = plan("jscut_pocket.gcode", "--work-offset-mm 212.132,-5", dir);
  ASSERT_FALSE(j.rows.empty());
  EXPECT_EQ(j.summary["laser_on_s"].get<double>(), 0.0);
  EXPECT_GE(j.summary["duration_s"].get<double>(), 40 / (1016 / 60.0) - 3 * fillet_saving_mm(0.02) / (1016 / 60.0));
  EXPECT_EQ(warnings_of(j.summary), (std::map<std::string, std::pair<int, int>>{{"z_ignored", {4, 4}}}));
  // svg2gcode: a circle of radius 4 mm in 0.02 mm chords at F3000 (50 mm/s), M4: within P of the
  // circle, and at 80 % of its feed or more on all but the speed changes at its ends.
  const Planned s = plan("svg2gcode_grbl.gcode", "--work-offset-mm 222.132,0", dir);
  ASSERT_FALSE(s.rows.empty());
  EXPECT_LE(laser_deviation_mm(s.rows, {arc(222.132, 0, 4, 0, 2 * pi)}), 0.02 + 1e-6);
  double fast = 0.0, total = 0.0;
  for (std::size_t k = 1; k < s.rows.size(); ++k) {
    if (s.rows[k].laser == 0) continue;
    const double step = std::hypot(s.rows[k].x - s.rows[k - 1].x, s.rows[k].y - s.rows[k - 1].y);
    total += step;
    fast += std::hypot(s.rows[k].vx, s.rows[k].vy) >= 0.8 * 50.0 ? step : 0.0;
  }
  // A closed path within P of the circle, around its centre, is at least as long as the circle of R − P.
  EXPECT_GE(total, 2 * pi * (4 - 0.02) - 0.05);
  EXPECT_LE(total, 2 * pi * 4 + 0.05);
  EXPECT_GE(fast, total - 2 * 0.5);  // at 5 g, 50 mm/s is reached within 0.5 mm of each end
}

// The drawn staircase of a LaserWeb-style file: its G1 vertices (a plain reading of this one format).
Polyline staircase_of(const fs::path& file, double ox, double oy) {
  std::ifstream in(file);
  Polyline p;
  const std::regex move(R"(^G[01] X(-?[0-9.]+) Y(-?[0-9.]+))");
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_search(line, m, move)) p.push_back({ox + std::stod(m[1]), oy + std::stod(m[2])});
  }
  return p;
}

TEST(CliPlanFamilies, LaserWebStaircaseRunsNearItsFeedWithinTheTolerance) {
  // A circle of radius 2 mm flattened at 0.01 mm and written with two decimals: 1 200 steps of 0.01 and
  // 0.014 mm at F10000 (166.7 mm/s). Merged within half the default tolerance (0.01 mm) and blended, it
  // runs at 80 % of its feed or more on all but its ends, within 0.02 mm of the staircase; before, each
  // step was a corner (a mean 17 mm/s on LaserWeb's own output).
  TempDir dir;
  const Planned p = plan("laserweb_staircase.gcode", "--work-offset-mm 222.132,0", dir);
  ASSERT_FALSE(p.rows.empty());
  const Polyline steps = staircase_of(cam / "laserweb_staircase.gcode", 222.132, 0);
  ASSERT_GT(steps.size(), 1000u);
  EXPECT_LE(laser_deviation_mm(p.rows, {steps}), 0.02 + 1e-6);
  // Each vertex of the staircase lies within the tolerance of the marked path too.
  std::vector<std::array<double, 2>> marked;
  for (const Row& r : p.rows) {
    if (r.laser == 1) marked.push_back({r.x, r.y});
  }
  double vertex_worst = 0.0;
  for (const auto& v : steps) vertex_worst = std::max(vertex_worst, distance_to(marked, v[0], v[1]));
  EXPECT_LE(vertex_worst, 0.02 + 0.0005);  // + the path between two samples (at most 0.08 mm apart)
  double fast = 0.0, total = 0.0;
  for (std::size_t k = 1; k < p.rows.size(); ++k) {
    if (p.rows[k].laser == 0 || p.rows[k - 1].laser == 0) continue;
    const double step = std::hypot(p.rows[k].x - p.rows[k - 1].x, p.rows[k].y - p.rows[k - 1].y);
    total += step;
    fast += std::hypot(p.rows[k].vx, p.rows[k].vy) >= 0.8 * 10000 / 60.0 ? step : 0.0;
  }
  EXPECT_GE(fast, 0.8 * total);
  const double ratio = p.summary["duration_s"].get<double>() / p.summary["slowdowns"]["programmed_time_s"].get<double>();
  EXPECT_LT(ratio, 1.3);
}

TEST(CliPlanFamilies, BlendOffStopsAtEveryCornerOfAProgramThatNamesNoMode) {
  TempDir dir;
  write_text(dir / "square.gcode", "G21 G90\nG0 X200 Y-20\nM3 S1000\nG1 X240 F1200\nY20\nX200\nY-20\nM5\n");
  const CliResult blended = run_cli("plan square.gcode -o b.csv --json", dir.path());
  const CliResult stopped = run_cli("plan square.gcode -o s.csv --json --blend off", dir.path());
  ASSERT_EQ(blended.exit_code, 0) << blended.err;
  ASSERT_EQ(stopped.exit_code, 0) << stopped.err;
  EXPECT_LT(blended.json()["duration_s"].get<double>(), stopped.json()["duration_s"].get<double>());
  for (const auto& [file, exact] : {std::pair{"b.csv", false}, std::pair{"s.csv", true}}) {
    double closest = INFINITY;
    for (const Row& r : read_rows(dir.path() / file)) closest = std::min(closest, std::hypot(r.x - 240, r.y + 20));
    if (exact) {
      EXPECT_LT(closest, 2e-4);  // at rest there: the nearest sample within j·T³/6 = 0.2 µm
    } else {
      EXPECT_GT(closest, 0.005);  // rounded (F1200: the fillet is passed at the feed)
      EXPECT_LE(closest, 0.02 + 0.001);  // P, and the path between two samples
    }
  }
  EXPECT_EQ(run_cli("plan square.gcode --blend sometimes", dir.path()).exit_code, 2);
}

TEST(CliPlanFamilies, VendorMCodesAreIgnoredAsConfiguredAndRefusedOtherwise) {
  TempDir dir;
  write_text(dir / "job.gcode", "G21 G90\nG0 X200 Y0\nM100 P1 Q2\nM67 E0 Q50\nM300 S440 P100\nG1 X210 F600\n");
  const CliResult beep = run_cli("plan job.gcode", dir.path());
  EXPECT_EQ(beep.exit_code, 2);
  EXPECT_EQ(beep.err, "error: job.gcode:5:1: M300: unsupported M code\n");
  const CliResult mapped = run_cli("plan job.gcode --ignore-m M100,M67,M300 --json", dir.path());
  ASSERT_EQ(mapped.exit_code, 0) << mapped.err;
  EXPECT_EQ(warnings_of(mapped.json()), (std::map<std::string, std::pair<int, int>>{{"m_code_ignored", {3, 3}}}));
  const CliResult none = run_cli("plan job.gcode --ignore-m none", dir.path());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("job.gcode:3:1: M100: unsupported M code"), std::string::npos) << none.err;
  EXPECT_NE(none.err.find("job.gcode:4:5: E0: unsupported word"), std::string::npos) << none.err;
  const CliResult own = run_cli("plan job.gcode --ignore-m M3", dir.path());
  EXPECT_EQ(own.exit_code, 2);
  EXPECT_NE(own.err.find("--ignore-m"), std::string::npos) << own.err;
  EXPECT_EQ(run_cli("plan job.gcode --outputs P0=led", dir.path()).exit_code, 2);
}

TEST(CliPlanFamilies, PairOptionsBeforeTheJobDoNotTakeItsName) {
  TempDir dir;
  write_text(dir / "job.gcode", "G21 G90\nG0 X0 Y0\nM3 S1000\nG1 X10 F600\nM5\n");
  const CliResult before = run_cli("plan --work-offset-mm 212.132,0 job.gcode -o a.csv --json", dir.path());
  ASSERT_EQ(before.exit_code, 0) << before.err;
  const CliResult after = run_cli("plan job.gcode --work-offset-mm 212.132,0 -o b.csv --json", dir.path());
  ASSERT_EQ(after.exit_code, 0) << after.err;
  EXPECT_EQ(before.json()["duration_s"], after.json()["duration_s"]);
  EXPECT_EQ(run_cli("plan --start-mm 200,0 --work-offset-mm 212.132,0 job.gcode -o c.csv", dir.path()).exit_code, 0);
  EXPECT_EQ(read_rows(dir.path() / "c.csv").front().x, 200.0);
  const CliResult negative = run_cli("plan --work-offset-mm=-10,5 job.gcode", dir.path());
  EXPECT_EQ(negative.exit_code, 2);  // (-10, 5) puts the job outside the workspace, and says so
  EXPECT_NE(negative.err.find("outside robot oc-gu's workspace"), std::string::npos) << negative.err;
  const CliResult three = run_cli("plan job.gcode --work-offset-mm 1,2,3", dir.path());
  EXPECT_EQ(three.exit_code, 2);
  EXPECT_NE(three.err.find("--work-offset-mm: expected X,Y in mm"), std::string::npos) << three.err;
  const CliResult run = run_cli("run --work-offset-mm 212.132,0 job.gcode --no-compensation -o j.csv", dir.path());
  EXPECT_EQ(run.exit_code, 0) << run.err;
}

TEST(CliPlanFamilies, TheSampleCapOnlyBoundsWhatIsWritten) {
  TempDir dir;
  write_text(dir / "dwell.gcode", "G0 X200 Y0\nG4 P10\n");  // 20 001 samples
  EXPECT_EQ(run_cli("plan dwell.gcode --max-samples 20000 -o out.csv", dir.path()).exit_code, 2);
  const CliResult counted = run_cli("plan dwell.gcode --max-samples 20000 --json", dir.path());
  ASSERT_EQ(counted.exit_code, 0) << counted.err;
  EXPECT_EQ(counted.json()["samples"].get<int>(), 20001);
  // Without output the work is bounded: 300 dwells of an hour are 2.16e9 samples, refused before one is made.
  std::string long_job = "G0 X200 Y0\n";
  for (int k = 0; k < 300; ++k) long_job += "G4 P3600\n";
  write_text(dir / "long.gcode", long_job);
  const CliResult refused = run_cli("plan long.gcode", dir.path(), 60);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(refused.err, "error: long.gcode: the plan has 2160000001 samples (1080000.0 s at 2000 Hz), more than the "
                         "1000000000 a job that writes nothing may make (its work bound)\n");
}

TEST(CliPlanFamilies, OverlongLinesAndEndlessFilesAreRefusedEarly) {
  TempDir dir;
  std::string g1;
  for (int k = 0; k < 100'000; ++k) g1 += "G1";  // 200 000 bytes on one line
  write_text(dir / "g1.gcode", "G0 X200 Y0\n" + g1 + "\nG1 X210 F600\n");
  const CliResult r = run_cli("plan g1.gcode -o out.csv", dir.path(), 60);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "error: g1.gcode:2:65537: the line is longer than 65536 bytes, the longest accepted; reading stops here\n");
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
  const CliResult zero = run_cli("plan /dev/zero", dir.path(), 60);
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_EQ(zero.err, "error: /dev/zero:1:65537: the line is longer than 65536 bytes, the longest accepted; reading stops here\n");
  // A long line within the bound: every refusal counted, 20 kept and shown.
  std::string many;
  for (int k = 0; k < 30'000; ++k) many += "G1";
  write_text(dir / "many.gcode", "G0 X200 Y0\n" + many + "\n");
  const CliResult counted = run_cli("plan many.gcode", dir.path(), 60);
  EXPECT_EQ(counted.exit_code, 2);
  EXPECT_NE(counted.err.find("error: many.gcode:2:3: G1: a second motion word on one line (G1 at column 1)\n"),
            std::string::npos);
  EXPECT_NE(counted.err.find("… and 29979 more\n"), std::string::npos) << counted.err.substr(0, 300);
}

}  // namespace
}  // namespace stiffpath::test
