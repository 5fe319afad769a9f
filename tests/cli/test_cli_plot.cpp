// End-to-end tests of the figures: plot run|mark|results|compliance, experiment figures, axes and titles read from the kept scripts and SVG text.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "cli_runner.hpp"
#include "stiffpath/report/gnuplot.hpp"

namespace stiffpath::test {
namespace {

const std::string kExamples = std::string(STIFFPATH_SOURCE_DIR) + "/examples/";

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

// Numeric rows of a tab-separated data file ('#' lines skipped); `block` counts blocks separated by two blank lines.
std::vector<std::vector<double>> rows_of(const std::filesystem::path& path, int block = -1) {
  std::ifstream in(path);
  std::vector<std::vector<double>> rows;
  int current = 0, blanks = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) {
      if (++blanks == 2) ++current;
      continue;
    }
    blanks = 0;
    if (line[0] == '#' || (block >= 0 && current != block)) continue;
    std::stringstream ss(line);
    std::vector<double> row;
    for (double x; ss >> x;) row.push_back(x);
    rows.push_back(row);
  }
  return rows;
}

// Every figure comes as SVG, PNG and its kept script, which sets text literal (no enhanced-text markup).
void expect_figure(const std::filesystem::path& dir, const std::string& name) {
  for (const char* ext : {".svg", ".png", ".gp"}) EXPECT_TRUE(std::filesystem::exists(dir / (name + ext))) << name << ext;
  const std::string gp = read_text(dir / (name + ".gp"));
  EXPECT_TRUE(contains(gp, "noenhanced")) << name;
  EXPECT_FALSE(contains(gp, "(um")) << name << ": micrometres written as um";
  EXPECT_FALSE(contains(read_text(dir / (name + ".svg")), "<tspan")) << name << ": enhanced text markup in the SVG";
}

#define SKIP_WITHOUT_GNUPLOT() \
  if (!report::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed"

TEST(CliPlot, RunShowsThePlannedMotionWithUnitsAndPhysicalPeaks) {
  SKIP_WITHOUT_GNUPLOT();
  TempDir dir;
  ASSERT_EQ(run_cli("run " + kExamples + "y_motion.gcode --accel 5g -o joints.csv", dir.path()).exit_code, 0);
  const CliResult r = run_cli("plot run joints.csv -o figs --max-points 800", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto figs = dir.path() / "figs";
  expect_figure(figs, "run_joints_motion");
  expect_figure(figs, "run_joints_joints");
  const std::string gp = read_text(figs / "run_joints_motion.gp");
  for (const char* label : {"'position (mm)'", "'path speed (mm/s)'", "'acceleration (m/s²)'", "'jerk (m/s³)'",
                            "'D''Alembert force (N)'", "'deflection, correction (µm)'", "'t (s)'"}) {
    EXPECT_TRUE(contains(gp, std::string("set ylabel ") + label) || contains(gp, std::string("set xlabel ") + label))
        << label;
  }
  const std::string joints_gp = read_text(figs / "run_joints_joints.gp");
  for (const char* label : {"'joint angle (rad)'", "'joint velocity (rad/s)'", "(rad/s²)'"}) EXPECT_TRUE(contains(joints_gp, label));
  EXPECT_TRUE(contains(gp, "'N")) << "G-code line markers";
  // Bounded: at most 2 × max-points rows however long the run.
  const auto rows = rows_of(figs / "run_joints.tsv");
  EXPECT_LE(rows.size(), 1600U);
  EXPECT_GE(rows.size(), 200U);  // 243 samples: all of them
  // The physics, independent of the code: F120000 mm/min = 2000 mm/s is reached on 150 mm at 5 g; the
  // planner's acceleration limit is 5 g = 49.03 m/s²; the force is m·a with the platform's 3.6 kg.
  double speed = 0, acc = 0, force = 0;
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 23U);
    speed = std::max(speed, row[5]);
    acc = std::max(acc, row[7]);
    force = std::max(force, std::hypot(row[11], row[12]));
    EXPECT_NEAR(row[13], -row[15], 1e-6);  // gain 1: predicted Δ = p − p_cmd = −correction
    EXPECT_NEAR(row[14], -row[16], 1e-6);
  }
  EXPECT_NEAR(speed, 2000.0, 20.0);
  EXPECT_NEAR(acc, 5 * 9.80665, 0.05 * 5 * 9.80665);
  EXPECT_NEAR(force, 3.6 * 5 * 9.80665, 0.05 * 3.6 * 5 * 9.80665);
  // Decimated to 100 buckets (at most 200 rows), the peaks are the same.
  ASSERT_EQ(run_cli("plot run joints.csv -o small --max-points 100", dir.path()).exit_code, 0);
  const auto few = rows_of(dir.path() / "small" / "run_joints.tsv");
  EXPECT_LE(few.size(), 200U);
  EXPECT_LT(few.size(), rows.size());
  double few_speed = 0, few_acc = 0;
  for (const auto& row : few) few_speed = std::max(few_speed, row[5]), few_acc = std::max(few_acc, row[7]);
  EXPECT_DOUBLE_EQ(few_speed, speed);
  EXPECT_DOUBLE_EQ(few_acc, acc);
}

TEST(CliPlot, ResultsOfYourOwnScansAreDrawnAsMeasuredWithTheirNumbers) {
  SKIP_WITHOUT_GNUPLOT();
  TempDir dir;
  std::ofstream(dir.path() / "scans.csv") << "# my plate, scanned at 1200 dpi\n"
                                             "robot,motion,compensated,acceleration_g,length_mm,deviation_area_mm2,source\n"
                                             "oc,y,0,1,149.91,0.52,measured\n"
                                             "oc,y,0,3,149.70,1.40,measured\n"
                                             "oc,y,1,3,149.96,0.31,measured\n"
                                             "oc,y,1,1,149.99,0.12,measured\n";
  const CliResult r = run_cli("plot results scans.csv -o figs --style paper", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto figs = dir.path() / "figs";
  expect_figure(figs, "fig_4_9a_y_length");
  expect_figure(figs, "fig_4_9b_y_deviation");
  EXPECT_FALSE(std::filesystem::exists(figs / "fig_4_10a_x_length.svg"));  // no x rows
  const std::string svg = read_text(figs / "fig_4_9a_y_length.svg");
  EXPECT_TRUE(contains(svg, "y motion: length of the measured marks (cf. fig. 4.9a)"));
  EXPECT_FALSE(contains(svg, "simulated"));
  EXPECT_TRUE(contains(svg, "path acceleration (g)"));
  EXPECT_TRUE(contains(read_text(figs / "fig_4_9b_y_deviation.svg"), "deviation area (mm²)"));
  const std::string gp = read_text(figs / "fig_4_9a_y_length.gp");
  EXPECT_TRUE(contains(gp, "set monochrome"));  // paper style
  EXPECT_TRUE(contains(gp, "serif,18"));
  // Blocks: without compensation sorted by acceleration, then with.
  const auto off = rows_of(figs / "fig_4_9a_y_length.tsv", 0), on = rows_of(figs / "fig_4_9a_y_length.tsv", 1);
  ASSERT_EQ(off.size(), 2U);
  ASSERT_EQ(on.size(), 2U);
  EXPECT_DOUBLE_EQ(off[1][0], 3.0);
  EXPECT_DOUBLE_EQ(off[1][1], 149.70);
  EXPECT_DOUBLE_EQ(on[0][2], 0.12);
}

TEST(CliPlot, ResultsWithoutProvenanceOrWithBadCellsAreRefused) {
  TempDir dir;
  std::ofstream(dir.path() / "a.csv") << "robot,motion,compensated,acceleration_g,length_mm,deviation_area_mm2\n"
                                         "oc,y,0,1,149.9,0.5\n";
  const CliResult none = run_cli("plot results a.csv -o figs", dir.path());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_TRUE(contains(none.err, "simulated or measured")) << none.err;
  std::ofstream(dir.path() / "b.csv") << "robot,motion,compensated,acceleration_g,length_mm,deviation_area_mm2\n"
                                         "oc,y,0,1,149.9,0.5\noc,y,2,1,149.9,0.5\n";
  const CliResult bad = run_cli("plot results b.csv --source measured -o figs", dir.path());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(contains(bad.err, "b.csv:3:")) << bad.err;
  EXPECT_TRUE(contains(bad.err, "must be 0 or 1, got 2")) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "figs" / "fig_4_9a_y_length.svg"));
}

TEST(CliPlot, MarkShowsAMeasuredOffsetAtItsSize) {
  SKIP_WITHOUT_GNUPLOT();
  TempDir dir;
  ASSERT_EQ(run_cli("run " + kExamples + "y_motion.gcode --accel 2g -o joints.csv", dir.path()).exit_code, 0);
  // A hand-made "scan": the commanded line x = 222.132 mm shifted by 40 µm to +x, so 40 µm to the right of travel (+y).
  std::ofstream mark(dir.path() / "mark.csv");
  mark << "x_mm,y_mm\n";
  for (int k = 0; k <= 300; ++k) mark << 222.172 << "," << -75.0 + 0.5 * k << "\n";
  mark.close();
  const CliResult r = run_cli("plot mark joints.csv --mark mark.csv --source measured -o figs", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_figure(dir.path() / "figs", "mark_joints");
  const std::string svg = read_text(dir.path() / "figs" / "mark_joints.svg");
  EXPECT_TRUE(contains(svg, "measured mark over the commanded path (max deviation 40.0 µm"));
  EXPECT_TRUE(contains(svg, "µm of deviation (x"));  // the scale bar
  EXPECT_TRUE(contains(svg, "deviation (µm), left positive"));
  for (const auto& row : rows_of(dir.path() / "figs" / "mark_joints.tsv", 2)) EXPECT_NEAR(row[1], -40.0, 0.01);
  const CliResult unsaid = run_cli("plot mark joints.csv --mark mark.csv -o figs2", dir.path());
  EXPECT_EQ(unsaid.exit_code, 2);
}

TEST(CliPlot, SimulatedMarkSaysSimulated) {
  SKIP_WITHOUT_GNUPLOT();
  TempDir dir;
  ASSERT_EQ(run_cli("run " + kExamples + "y_motion.gcode --accel 5g --no-compensation -o joints.csv", dir.path()).exit_code, 0);
  const CliResult r = run_cli("plot mark joints.csv -o figs --quiet", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string svg = read_text(dir.path() / "figs" / "mark_joints.svg");
  EXPECT_TRUE(contains(svg, "simulated mark over the commanded path"));
  EXPECT_FALSE(contains(svg, "measured"));
}

TEST(CliPlot, CompliancePlotKeepsUnderscoresAndMicrometres) {
  SKIP_WITHOUT_GNUPLOT();
  TempDir dir;
  ASSERT_EQ(run_cli("fit --robot oc-gu --method physical -o my_phys.json", dir.path()).exit_code, 0);
  const CliResult r = run_cli("plot compliance --robot oc-gu --model my_phys.json -o figs", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_figure(dir.path() / "figs", "compliance_my_phys");
  const std::string svg = read_text(dir.path() / "figs" / "compliance_my_phys.svg");
  EXPECT_TRUE(contains(svg, "my_phys.json")) << "the model's file name, literally";
  EXPECT_TRUE(contains(svg, "largest compliance eigenvalue (µm/N)"));
  EXPECT_TRUE(contains(svg, "bars: principal directions, length ∝ compliance"));
  EXPECT_TRUE(contains(svg, "x (mm)") && contains(svg, "y (mm)"));
}

TEST(CliPlot, ExperimentFiguresSaySimulatedAndKeepTheirDataInOneFolder) {
  SKIP_WITHOUT_GNUPLOT();
  TempDir dir;
  const CliResult r = run_cli("experiment -o out --robots oc-gu --motions y --accelerations-g 1 3 --quiet", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> top;
  for (const auto& e : std::filesystem::directory_iterator(dir.path() / "out")) top.push_back(e.path().filename().string());
  std::sort(top.begin(), top.end());
  EXPECT_EQ(top, (std::vector<std::string>{"figures", "results.csv", "summary.md"}));
  const std::string summary = read_text(dir.path() / "out" / "summary.md");
  EXPECT_TRUE(contains(summary, "At 1 g") && contains(summary, "At 3 g")) << summary;
  const auto figs = dir.path() / "out" / "figures";
  expect_figure(figs, "fig_4_9a_y_length");
  const std::string svg = read_text(figs / "fig_4_9b_y_deviation.svg");
  EXPECT_TRUE(contains(svg, "of the simulated marks"));
  EXPECT_FALSE(contains(svg, "measured"));
  // plot results on the experiment's own table draws the same figure data (its source column says simulated).
  ASSERT_EQ(run_cli("plot results out/results.csv -o again", dir.path()).exit_code, 0);
  EXPECT_EQ(read_text(dir.path() / "again" / "fig_4_9b_y_deviation.tsv"), read_text(figs / "fig_4_9b_y_deviation.tsv"));
}

}  // namespace
}  // namespace stiffpath::test
