// End to end: `stiffpath run` → `stiffpath simulate` on the y motion, and `stiffpath experiment` on a reduced matrix.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

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
    if (line.back() == ',') cells.emplace_back();  // an empty last cell: no variant without compensation
    ASSERT_EQ(cells.size(), 18U);
    EXPECT_EQ(cells[17], cells[3] == "1" ? "thesis" : "");  // the compensation variant
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
