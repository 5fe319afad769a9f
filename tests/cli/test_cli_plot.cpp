// End-to-end tests of the figures and the report: plot run|mark|results|compliance, experiment figures, robot checks and bad input, read from the kept scripts, data and SVG text.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

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
    ASSERT_EQ(row.size(), 24U);
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

// The robot's geometry hash as the joint file's header records it (`# stiffpath joints … geometry_sha256=…`).
std::string recorded_hash(const std::filesystem::path& joints) {
  const std::string head = read_text(joints).substr(0, 400);
  const auto at = head.find("geometry_sha256=");
  return at == std::string::npos ? std::string() : head.substr(at + 16, 64);
}

// A joint limit of a preset, read from its robot file's text (not through the library).
double preset_limit(const std::string& robot, const std::string& key) {
  const std::string json = read_text(std::string(STIFFPATH_SOURCE_DIR) + "/data/robots/" + robot + ".json");
  const auto at = json.find("\"" + key + "\"");
  return at == std::string::npos ? NAN : std::stod(json.substr(json.find(':', at) + 1));
}

TEST(CliPlot, RunShowsLaserPowerRecordedAlphaAndTheRobotsLimits) {
  SKIP_WITHOUT_GNUPLOT();
  TempDir dir;
  // Half power (S500 of s_max 1000) on a 100 mm line; the run's default: dynamic compensation, smoothed.
  std::ofstream(dir.path() / "half.gcode") << "G21 G90\nG0 X222.132 Y-50\nM3 S500\nG1 Y50 F60000\nM5\nM2\n";
  ASSERT_EQ(run_cli("run half.gcode --accel 3g -o half.csv", dir.path()).exit_code, 0);
  const CliResult r = run_cli("plot run half.csv -o figs", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto figs = dir.path() / "figs";
  const std::string gp = read_text(figs / "run_half_motion.gp"), joints_gp = read_text(figs / "run_half_joints.gp");
  EXPECT_TRUE(contains(gp, "set ylabel 'laser power (%)'"));
  // The title names the robot and the geometry the joint file records.
  const std::string hash = recorded_hash(dir.path() / "half.csv");
  ASSERT_EQ(hash.size(), 64U);
  EXPECT_TRUE(contains(gp, "half.csv on oc-gu (geometry " + hash.substr(0, 12) + ")")) << hash;
  EXPECT_TRUE(contains(r.out, "robot oc-gu (geometry " + hash.substr(0, 12)));
  // oc-gu's limits, from its robot file: ±40 rad/s, ±4000 rad/s² drawn dashed.
  const double w = preset_limit("oc-gu", "max_velocity_rad_s"), al = preset_limit("oc-gu", "max_acceleration_rad_s2");
  EXPECT_TRUE(contains(joints_gp, fmt::format("{:.9g} with lines", w)) && contains(joints_gp, fmt::format("{:.9g} with lines", -w)));
  EXPECT_TRUE(contains(joints_gp, fmt::format("{:.9g} with lines", al)));
  EXPECT_TRUE(contains(joints_gp, "'joint acceleration (rad/s²)'")) << "α as recorded, not by differences";
  const auto rows = rows_of(figs / "run_half.tsv");
  ASSERT_GT(rows.size(), 100U);  // fewer samples than --max-points: every sample, undecimated
  int on = 0;
  double alpha_error = 0.0, alpha_peak = 0.0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), 24U);
    const double power = rows[k][23];
    EXPECT_TRUE(power == 0.0 || std::abs(power - 50.0) < 1e-9) << power;
    on += power > 0 ? 1 : 0;
    // The plotted α is the recorded one (the CSV's alpha1_rad_s2 column, same sample), and it is the
    // rate of the recorded ω: over two steps the mean of ω's slope lies within the range of the three α
    // samples (mean value theorem), up to the terms the dynamic method drops (≈2 % of the peak).
    if (k > 0 && k + 1 < rows.size()) {
      const double dt = rows[k + 1][0] - rows[k - 1][0];
      const double slope = (rows[k + 1][19] - rows[k - 1][19]) / dt;
      const auto [lo, hi] = std::minmax({rows[k - 1][21], rows[k][21], rows[k + 1][21]});
      alpha_error = std::max({alpha_error, lo - slope, slope - hi});
      alpha_peak = std::max(alpha_peak, std::abs(rows[k][21]));
    }
  }
  std::vector<double> recorded;
  {
    std::ifstream csv(dir.path() / "half.csv");
    std::string line;
    std::getline(csv, line), std::getline(csv, line);
    ASSERT_TRUE(contains(line, ",alpha1_rad_s2,")) << line;
    for (; std::getline(csv, line);) {
      std::stringstream cells(line);
      std::string cell;
      for (int c = 0; c <= 5 && std::getline(cells, cell, ','); ++c) {
        if (c == 5) recorded.push_back(std::stod(cell));
      }
    }
  }
  ASSERT_EQ(recorded.size(), rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) EXPECT_NEAR(rows[k][21], recorded[k], 1e-6) << k;
  EXPECT_GT(on, 50);
  EXPECT_GT(alpha_peak, 10.0);
  EXPECT_LT(alpha_error, 0.03 * alpha_peak) << "recorded α is dω/dt";
  EXPECT_TRUE(contains(r.out, "at up to 50 % power"));
}

TEST(CliPlot, RunAndMarkRefuseAJointFileOfAnotherRobotUnlessForced) {
  SKIP_WITHOUT_GNUPLOT();
  TempDir dir;
  ASSERT_EQ(run_cli("run " + kExamples + "y_motion.gcode --accel 2g -o joints.csv", dir.path()).exit_code, 0);
  for (const char* what : {"run", "mark"}) {
    const CliResult refused = run_cli(std::string("plot ") + what + " joints.csv --robot sc-gu -o figs", dir.path());
    EXPECT_EQ(refused.exit_code, 2) << what;
    EXPECT_TRUE(contains(refused.err, "joints.csv: ") && contains(refused.err, "written for robot 'oc-gu'") &&
                contains(refused.err, "--force-robot"))
        << refused.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "figs")) << "nothing written";
  }
  const CliResult forced = run_cli("plot run joints.csv --robot sc-gu --force-robot -o figs", dir.path());
  ASSERT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_TRUE(contains(read_text(dir.path() / "figs" / "run_joints_motion.gp"), "joints.csv on sc-gu"));
  // A file that records no robot: the default robot, said on stderr, never silently.
  std::ifstream in(dir.path() / "joints.csv");
  std::ofstream out(dir.path() / "anon.csv");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#", 0) != 0) out << line << "\n";
  }
  out.close();
  const CliResult anon = run_cli("plot run anon.csv -o figs2", dir.path());
  ASSERT_EQ(anon.exit_code, 0) << anon.err;
  EXPECT_TRUE(contains(anon.err, "does not record its robot; using the default robot 'oc-gu'")) << anon.err;
}

TEST(CliPlot, BadInputNamesTheFileAndWritesNothing) {
  TempDir dir;
  const CliResult missing = run_cli("plot run nowhere.csv -o figs", dir.path());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_TRUE(contains(missing.err, "nowhere.csv")) << missing.err;
  // A results table without the length column: the header line and the missing name.
  std::ofstream(dir.path() / "cols.csv") << "robot,motion,compensated,acceleration_g,length,deviation_area_mm2,source\n"
                                            "oc,y,0,1,149.9,0.5,measured\n";
  const CliResult columns = run_cli("plot results cols.csv -o figs", dir.path());
  EXPECT_EQ(columns.exit_code, 2);
  EXPECT_TRUE(contains(columns.err, "cols.csv:1:") && contains(columns.err, "missing column 'length_mm'")) << columns.err;
  // A negative area on line 3, column 6.
  std::ofstream(dir.path() / "neg.csv") << "robot,motion,compensated,acceleration_g,length_mm,deviation_area_mm2\n"
                                           "oc,y,0,1,149.9,0.5\noc,y,1,1,149.9,-0.5\n";
  const CliResult negative = run_cli("plot results neg.csv --source measured -o figs", dir.path());
  EXPECT_EQ(negative.exit_code, 2);
  EXPECT_TRUE(contains(negative.err, "neg.csv:3:") && contains(negative.err, "negative")) << negative.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "figs"));
  // -o onto a file: refused, the file untouched.
  std::ofstream(dir.path() / "taken") << "mine\n";
  std::ofstream(dir.path() / "good.csv") << "robot,motion,compensated,acceleration_g,length_mm,deviation_area_mm2\n"
                                            "oc,y,0,1,149.9,0.5\n";
  const CliResult onto = run_cli("plot results good.csv --source measured -o taken", dir.path());
  EXPECT_EQ(onto.exit_code, 2);
  EXPECT_TRUE(contains(onto.err, "taken") && contains(onto.err, "not a directory")) << onto.err;
  EXPECT_EQ(read_text(dir.path() / "taken"), "mine\n");
  const CliResult report = run_cli("report --robot oc-gu -o taken --quiet", dir.path());
  EXPECT_EQ(report.exit_code, 2);
  EXPECT_TRUE(contains(report.err, "not a directory")) << report.err;
  EXPECT_EQ(read_text(dir.path() / "taken"), "mine\n");
}

TEST(CliPlot, ResultsKeepEachCompensationVariantApart) {
  SKIP_WITHOUT_GNUPLOT();
  TempDir dir;
  std::ofstream(dir.path() / "v.csv") << "robot,motion,compensated,acceleration_g,length_mm,deviation_area_mm2,variant,source\n"
                                         "oc,x,0,1,149.0,0.9,,simulated\n"
                                         "oc,x,1,1,149.5,0.4,thesis,simulated\n"
                                         "oc,x,1,1,149.8,0.2,default,simulated\n";
  const CliResult r = run_cli("plot results v.csv -o figs", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto file = dir.path() / "figs" / "fig_4_10a_x_length.tsv";
  ASSERT_EQ(rows_of(file, 0).size(), 1U);
  EXPECT_DOUBLE_EQ(rows_of(file, 1).at(0).at(1), 149.5);
  EXPECT_DOUBLE_EQ(rows_of(file, 2).at(0).at(1), 149.8);
  const std::string gp = read_text(dir.path() / "figs" / "fig_4_10a_x_length.gp");
  EXPECT_TRUE(contains(gp, "'oc with thesis compensation'") && contains(gp, "'oc with default compensation'")) << gp;
}

TEST(CliReport, ShowsTheJointFilesRobotAndGeometryAndRefusesAnother) {
  SKIP_WITHOUT_GNUPLOT();
  TempDir dir;
  ASSERT_EQ(run_cli("run " + kExamples + "y_motion.gcode --accel 2g --robot sc-gu -o joints.csv", dir.path()).exit_code, 0);
  const std::string hash = recorded_hash(dir.path() / "joints.csv");
  ASSERT_EQ(hash.size(), 64U);
  // No --robot: the report is on the robot the joint file records, not on the default oc-gu.
  const CliResult r = run_cli("report --joints joints.csv -o rep --quiet", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = read_text(dir.path() / "rep" / "report.html");
  EXPECT_TRUE(contains(html, "stiffpath report: sc-gu"));
  EXPECT_TRUE(contains(html, "robot sc-gu, same geometry as the robot above")) << "the joint file's own record";
  std::size_t hashes = 0;
  for (auto at = html.find(hash); at != std::string::npos; at = html.find(hash, at + 1)) ++hashes;
  EXPECT_GE(hashes, 2U) << "the robot's geometry hash and the one the joint file records";
  EXPECT_TRUE(contains(html, "(geometry " + hash.substr(0, 12) + ")")) << "in the subtitle and the run's figure titles";
  EXPECT_FALSE(contains(html, "the default robot"));
  // Another robot than the file's: refused, nothing written.
  const CliResult other = run_cli("report --robot oc-gu --joints joints.csv -o rep2 --quiet", dir.path());
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_TRUE(contains(other.err, "joints.csv: ") && contains(other.err, "--force-robot reports it anyway")) << other.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "rep2"));
  // No robot at all: the default, said on the page and on stderr.
  const CliResult plain = run_cli("report -o rep3 --quiet", dir.path());
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_TRUE(contains(plain.err, "no --robot given; reporting on the default robot 'oc-gu'")) << plain.err;
  EXPECT_TRUE(contains(read_text(dir.path() / "rep3" / "report.html"), "(the default robot"));
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
