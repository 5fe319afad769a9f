// End to end: `stiffpath run` → `stiffpath simulate` on the y motion, and `stiffpath experiment` on a reduced matrix.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace {

using stiffpath::test::run_cli;
using stiffpath::test::TempDir;

nlohmann::json simulate_y(const TempDir& dir, const std::string& run_flags, const std::string& accel) {
  const std::string job = std::string(STIFFPATH_SOURCE_DIR) + "/examples/y_motion.gcode";
  const auto run = run_cli("run " + job + " -o j.csv --accel " + accel + " " + run_flags, dir.path());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const auto sim = run_cli("simulate j.csv --json", dir.path());
  EXPECT_EQ(sim.exit_code, 0) << sim.err;
  return nlohmann::json::parse(sim.out);
}

TEST(CliSimulate, CompensatedYMotionTracksBetter) {
  TempDir dir;
  const auto off = simulate_y(dir, "--no-compensation", "5g");
  const auto on = simulate_y(dir, "", "5g");
  for (const char* key : {"length_mm", "deviation_area_mm2", "max_deviation_mm", "path_accuracy_mm",
                          "residual_vibration_mm"}) {
    ASSERT_TRUE(off.contains(key)) << key;
    ASSERT_TRUE(on[key].is_number()) << key;
  }
  EXPECT_NEAR(off["commanded_length_mm"].get<double>(), 150.0, 1e-3);
  // The uncompensated mark is longer than commanded (lag at the start, overshoot at the end).
  EXPECT_GT(off["length_mm"].get<double>(), 150.05);
  EXPECT_LT(std::abs(on["length_mm"].get<double>() - 150.0), 0.3 * (off["length_mm"].get<double>() - 150.0));
  EXPECT_LT(on["max_deviation_mm"].get<double>(), 0.5 * off["max_deviation_mm"].get<double>());
  EXPECT_LT(on["path_accuracy_mm"].get<double>(), 0.5 * off["path_accuracy_mm"].get<double>());
}

// The thesis's loop closed: the twin's mark drawn as a 1200 dpi scan and measured by `scan` gives the
// length `simulate` measured on the mark's points (hooked ends included).
TEST(CliSimulate, MarkRenderedAsAScanMeasuresTheSameLength) {
  TempDir dir;
  const std::string job = std::string(STIFFPATH_SOURCE_DIR) + "/examples/y_motion.gcode";
  ASSERT_EQ(run_cli("run " + job + " -o j.csv --accel 5g --no-compensation", dir.path()).exit_code, 0);
  const auto sim = run_cli("simulate j.csv --marks-csv marks.csv --json", dir.path());
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto metrics = nlohmann::json::parse(sim.out);
  std::ifstream marks(dir.path() / "marks.csv");
  std::string line;
  std::getline(marks, line);
  EXPECT_EQ(line, "x_mm,y_mm");
  std::size_t rows = 0;
  double y_max = -1e9;
  for (; std::getline(marks, line); ++rows) y_max = std::max(y_max, std::stod(line.substr(line.find(',') + 1)));
  EXPECT_EQ(rows, metrics["marked_points"].get<std::size_t>());
  EXPECT_NEAR(y_max, 75.0, 1e-6);  // the start (y = −75 mm on the robot) is at +75 mm, y down
  ASSERT_EQ(run_cli("render-scan --path-csv marks.csv scan.png", dir.path()).exit_code, 0);
  const auto scan = run_cli("scan scan.png --json", dir.path());
  ASSERT_EQ(scan.exit_code, 0) << scan.err;
  const auto measured = nlohmann::json::parse(scan.out);
  EXPECT_NEAR(measured["length_mm"].get<double>(), metrics["length_mm"].get<double>(), 0.010);
  EXPECT_GT(metrics["length_mm"].get<double>(), 150.05);  // the hooked, overshooting mark this is about
  EXPECT_TRUE(measured["warnings"].empty()) << measured["warnings"];
}

// A CAM job's lettering is many strokes: each is measured on its own (the travel moves between them
// are no longer corners of one path), and AT_p stays within the tip's deflection.
TEST(CliSimulate, RealisticJobIsMeasuredStrokeByStroke) {
  TempDir dir;
  const std::string job = std::string(STIFFPATH_SOURCE_DIR) + "/examples/nameplate.gcode";
  ASSERT_EQ(run_cli("run " + job + " -o j.csv --accel 2g", dir.path()).exit_code, 0);
  const auto sim = run_cli("simulate j.csv --json", dir.path());
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto m = nlohmann::json::parse(sim.out);
  EXPECT_GT(m["strokes"].get<int>(), 10);
  EXPECT_EQ(m["stroke_metrics"].size(), m["strokes"].get<std::size_t>());
  std::size_t marked = 0;
  for (const auto& s : m["stroke_metrics"]) marked += s["marked_points"].get<std::size_t>();
  EXPECT_EQ(marked, m["marked_points"].get<std::size_t>());
  EXPECT_GT(m["path_accuracy_mm"].get<double>(), 0.0);
  EXPECT_LT(m["path_accuracy_mm"].get<double>(), 1.0);
}

TEST(CliSimulate, BadFileIsAnError) {
  TempDir dir;
  std::ofstream(dir.path() / "bad.csv") << "t_s,theta1_rad\n0,abc\n";
  const auto r = run_cli("simulate bad.csv", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error:"), std::string::npos);
}

// `simulate` and a scan of its mark: the job run on `robot`, simulated (with `trim_mm` of corner trim), its
// mark rendered at 1200 dpi and scanned with the same trim.
struct MarkAndScan {
  nlohmann::json simulated, scanned;
};
MarkAndScan simulate_and_scan(const TempDir& dir, const std::string& job, const std::string& robot, int sides,
                              const std::string& shape, double trim_mm) {
  const std::string trim = " --corner-trim-mm " + std::to_string(trim_mm);
  const auto run = run_cli("run '" + job + "' --robot " + robot + " --accel 5g --no-compensation -o j.csv", dir.path());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const auto sim = run_cli("simulate j.csv --robot " + robot + " --marks-csv marks.csv --json" + trim, dir.path());
  EXPECT_EQ(sim.exit_code, 0) << sim.err;
  const auto render = run_cli("render-scan --path-csv marks.csv --sides " + std::to_string(sides) + " scan.png", dir.path());
  EXPECT_EQ(render.exit_code, 0) << render.err;
  const auto scan = run_cli("scan scan.png --json --shape " + shape + trim, dir.path());
  EXPECT_EQ(scan.exit_code, 0) << scan.err;
  return {nlohmann::json::parse(sim.out), nlohmann::json::parse(scan.out)};
}

// One definition of the mark's metrics, along the mark: a scan of the twin's mark measures what
// `simulate` measured on it, within 5 µm of length and maximum deviation. A triangle on a robot of
// one's own (not the thesis's), uncompensated at 5 g: hooked corners, vibration along the sides.
TEST(CliSimulate, AScanOfTheMarkMeasuresWhatSimulateMeasuredOnYourOwnRobot) {
  TempDir dir;
  std::ofstream(dir.path() / "tri.gcode") << "G21 G90 G61\nG0 X-40 Y185\nM3 S1000\nG1 X40 Y185 F60000\nG1 X0 Y240\n"
                                             "G1 X-40 Y185\nM5\n";
  const std::string robot = std::string(STIFFPATH_SOURCE_DIR) + "/examples/robots/asym_5bar.json";
  const auto m = simulate_and_scan(dir, (dir.path() / "tri.gcode").string(), "'" + robot + "'", 3, "triangle", 1.0);
  EXPECT_EQ(m.simulated["robot"], "asym-5bar");
  EXPECT_EQ(m.simulated["stroke_metrics"][0]["sides"], 3);
  EXPECT_NEAR(m.scanned["length_mm"].get<double>(), m.simulated["length_mm"].get<double>(), 0.005);
  EXPECT_NEAR(m.scanned["max_deviation_mm"].get<double>(), m.simulated["max_deviation_mm"].get<double>(), 0.005);
  EXPECT_GT(m.simulated["max_deviation_mm"].get<double>(), 0.02);  // a mark with something to measure
  EXPECT_TRUE(m.scanned["warnings"].empty()) << m.scanned["warnings"];
}

// The thesis's triangle at 5 g without compensation (the demo's): its corners overshoot so far that a scan
// measures its sides only from 1.3 mm of the corners on; with that trim both agree (before, `simulate`
// weighed the mark by time: 320.5195 against the scan's 320.559 mm, max deviation 0.312 against 0.350 mm).
TEST(CliSimulate, AScanOfTheThesisTriangleMeasuresWhatSimulateMeasured) {
  TempDir dir;
  const auto m = simulate_and_scan(dir, std::string(STIFFPATH_SOURCE_DIR) + "/examples/triangle.gcode", "oc-gu", 3,
                                   "triangle", 1.3);
  EXPECT_NEAR(m.scanned["length_mm"].get<double>(), m.simulated["length_mm"].get<double>(), 0.005);
  EXPECT_NEAR(m.scanned["max_deviation_mm"].get<double>(), m.simulated["max_deviation_mm"].get<double>(), 0.005);
  EXPECT_GT(m.simulated["length_error_mm"].get<double>(), 0.3);
  EXPECT_TRUE(m.scanned["warnings"].empty()) << m.scanned["warnings"];
}

// Joint commands the robot cannot take are refused where they are read: file, line, record, value, limit.
TEST(CliSimulate, JointCommandsBeyondTheLimitsAreRefusedWithTheirPlace) {
  TempDir dir;
  const std::string job = std::string(STIFFPATH_SOURCE_DIR) + "/examples/y_motion.gcode";
  ASSERT_EQ(run_cli("run " + job + " -o j.csv --accel 5g", dir.path()).exit_code, 0);
  std::ifstream in(dir.path() / "j.csv");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines[1].substr(0, 16), "t_s,theta1_rad,t");
  std::string& row = lines[101];  // line 102: record 100
  const auto a = row.find(','), b = row.find(',', a + 1);
  row = row.substr(0, a + 1) + "3.001966313" + row.substr(b);  // θ1 = 172°, the limit is 135°
  std::ofstream out(dir.path() / "bad.csv");
  for (const auto& line : lines) out << line << "\n";
  out.close();
  const auto r = run_cli("simulate bad.csv --marks-csv marks.csv", dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("bad.csv:102"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("record 100"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("theta1 = 172.000 deg"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("upper limit of 135.000 deg"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "marks.csv"));
  EXPECT_TRUE(r.out.empty()) << r.out;
}

// The work budget is stated before the work starts: a job beyond it is refused at once, naming its last
// record, its length and the limit.
TEST(CliSimulate, AJobBeyondTheWorkBudgetIsRefusedBeforeItStarts) {
  TempDir dir;
  const std::string job = std::string(STIFFPATH_SOURCE_DIR) + "/examples/y_motion.gcode";
  ASSERT_EQ(run_cli("run " + job + " -o j.csv --accel 5g", dir.path()).exit_code, 0);
  ASSERT_EQ(run_cli("run " + job + " -o j.bin --format bin --accel 5g", dir.path()).exit_code, 0);
  std::ifstream in(dir.path() / "j.csv");
  std::size_t lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  const auto csv = run_cli("simulate j.csv --max-steps 3000", dir.path());
  EXPECT_EQ(csv.exit_code, 2) << csv.err;
  EXPECT_NE(csv.err.find("j.csv:" + std::to_string(lines)), std::string::npos) << csv.err;
  EXPECT_NE(csv.err.find("work budget of 3000 steps"), std::string::npos) << csv.err;
  EXPECT_NE(csv.err.find("--max-steps"), std::string::npos) << csv.err;
  const auto bin = run_cli("simulate j.bin --max-steps 3000", dir.path());
  EXPECT_EQ(bin.exit_code, 2) << bin.err;
  EXPECT_NE(bin.err.find("record " + std::to_string(lines - 2) + " (byte"), std::string::npos) << bin.err;
  EXPECT_EQ(run_cli("simulate j.bin --max-steps 100000", dir.path()).exit_code, 0);
}

TEST(CliExperiment, ReducedMatrixWritesOneRowPerRun) {
  TempDir dir;
  const auto r = run_cli(
      "experiment -o out --mechanisms oc-gu sc-gu --motions y --accelerations-g 1 5 --variants thesis --no-plots",
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(dir.path() / "out" / "results.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("robot,rows,cg,compensated,motion,acceleration_g", 0), 0U);
  int rows = 0;
  double oc_off_5 = 0, oc_on_5 = 0, sc_off_5 = 0;
  while (std::getline(in, line)) {
    ++rows;
    std::stringstream ss(line);
    std::vector<std::string> cells;
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    ASSERT_EQ(cells.size(), 19U);
    EXPECT_EQ(cells[17], cells[3] == "1" ? "thesis" : "");  // the compensation variant
    EXPECT_EQ(cells[18], "simulated");
    EXPECT_TRUE(cells[13].empty() && cells[14].empty());  // a line has no corners: CR and CO left empty
    const double error = std::stod(cells[9]), g = std::stod(cells[5]);
    if (g != 5) continue;
    if (cells[0] == "oc-gu") (cells[3] == "1" ? oc_on_5 : oc_off_5) = error;
    if (cells[0] == "sc-gu" && cells[3] == "0") sc_off_5 = error;
  }
  EXPECT_EQ(rows, 2 * 2 * 1 * 2);
  EXPECT_GT(oc_off_5, 0.02);
  // The honest twin (loaded servos, a CG lever the model does not know): most of the error, not all of it.
  EXPECT_LT(std::abs(oc_on_5), 0.5 * oc_off_5);
  EXPECT_GT(sc_off_5, oc_off_5);  // SC is the more compliant build
  EXPECT_NE(r.out.find("| oc-gu | y | thesis |"), std::string::npos);
}

// The robustness sweep, CI-sized: one motion, two seeds, nominal + two off-nominal conditions, without and
// with the thesis's compensation: 3 × 2 × 1 rows of 2 runs each, and a sweep above --max-runs is refused.
TEST(CliExperiment, RobustnessSweepWritesTheStatedRows) {
  TempDir dir;
  const std::string sweep =
      "experiment --robustness -o rob --seeds 2 --damping-ratios 0.05 0.2 --mass-errors 0.25 "
      "--servo-bandwidths-hz 100 --noise-um 11.5 --robust-motions y-mid-1 --robust-variants without thesis "
      "--robust-accel-g 3 --no-plots";
  const auto r = run_cli(sweep, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(dir.path() / "rob" / "robustness.tsv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("factor\tvalue\tvariant\tmotion\truns\tworst_CO_um\tworst_ATp_um", 0), 0U);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::vector<std::string> cells;
    for (std::string c; std::getline(ss, c, '\t');) cells.push_back(c);
    ASSERT_EQ(cells.size(), 10U) << line;
    rows.push_back(cells);
  }
  ASSERT_EQ(rows.size(), 6U);
  const std::vector<std::pair<std::string, std::string>> conditions{
      {"nominal", "0"}, {"damping_ratio", "0.2"}, {"mass_error", "0.25"}};
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k][0], conditions[k / 2].first);
    EXPECT_EQ(rows[k][1], conditions[k / 2].second);
    EXPECT_EQ(rows[k][2], k % 2 == 0 ? "without" : "thesis");
    EXPECT_EQ(rows[k][3], "y-mid-1");
    EXPECT_EQ(rows[k][4], "2");
    EXPECT_EQ(std::stod(rows[k][5]), 0.0);  // a line has no corner
  }
  // At nominal, compensation lowers the worst path accuracy AT_p.
  EXPECT_LT(std::stod(rows[1][6]), std::stod(rows[0][6]));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "rob" / "robustness.md"));
  const auto refused = run_cli(sweep + " --max-runs 5", dir.path());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("more than the limit of 5"), std::string::npos) << refused.err;
}

}  // namespace
