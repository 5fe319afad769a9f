// End-to-end tests of `stiffpath plan` on the examples: numbers in the CSV and JSON checked independently.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "stiffpath/core/csv.hpp"

namespace stiffpath::test {
namespace {

namespace fs = std::filesystem;
const fs::path examples = fs::path(STIFFPATH_SOURCE_DIR) / "examples";
constexpr double g = 9.80665;

struct Row {
  double t, x, y, vx, vy, ax, ay, jx, jy;
  int laser, line;
};

std::vector<Row> read_trajectory(const fs::path& path) {
  core::CsvReader csv(path.string());
  const std::vector<std::string> expected = {"t_s", "x_mm", "y_mm", "vx_mm_s", "vy_mm_s", "ax_mm_s2", "ay_mm_s2",
                                             "jx_mm_s3", "jy_mm_s3", "laser", "power", "line"};
  EXPECT_EQ(csv.header(), expected);
  std::vector<Row> rows;
  while (csv.next()) {
    rows.push_back({csv.number(0), csv.number(1), csv.number(2), csv.number(3), csv.number(4), csv.number(5),
                    csv.number(6), csv.number(7), csv.number(8), static_cast<int>(csv.integer(9)),
                    static_cast<int>(csv.integer(11))});
  }
  return rows;
}

// Rest-to-rest duration of a move of L reaching both v and a (closed form): L/v + v/a + a/j.
double rest_to_rest_s(double L, double v, double a, double j) { return L / v + v / a + a / j; }

TEST(CliPlan, ThesisXMotionAt5gNumbersCheckedIndependently) {
  TempDir dir;
  const CliResult r = run_cli("plan '" + (examples / "x_motion.gcode").string() + "' -o traj.csv --json", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = r.json();
  const double a = 5 * g, j = a / 0.005, T = rest_to_rest_s(0.1, 2.0, a, j);
  EXPECT_EQ(summary["samples"].get<int>(), static_cast<int>(std::ceil(T * 2000)) + 1);
  EXPECT_NEAR(summary["duration_s"].get<double>(), std::ceil(T * 2000) / 2000, 1e-12);
  EXPECT_NEAR(summary["peak_acceleration_m_s2"].get<double>(), a, 1e-9);
  EXPECT_NEAR(summary["peak_jerk_m_s3"].get<double>(), j, 1e-6);
  EXPECT_NEAR(summary["peak_velocity_m_s"].get<double>(), 2.0, 1e-12);

  const auto rows = read_trajectory(dir / "traj.csv");
  ASSERT_EQ(rows.size(), summary["samples"].get<std::size_t>());
  EXPECT_EQ(rows.front().x, 172.132);
  EXPECT_EQ(rows.back().x, 272.132);
  EXPECT_EQ(rows.back().vx, 0.0);
  double travelled = 0.0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k].y, 0.0);
    EXPECT_LE(std::abs(rows[k].vx), 2000.0 + 1e-6);
    EXPECT_LE(std::abs(rows[k].ax), a * 1e3 * (1 + 1e-9));
    EXPECT_EQ(rows[k].laser, 1);
    EXPECT_EQ(rows[k].line, 8);
    if (k > 0) travelled += 0.5 * (rows[k].vx + rows[k - 1].vx) * 0.0005;  // trapezoidal rule
    if (k > 0 && k + 1 < rows.size()) {  // central differences of the positions against the velocities
      const double vx_numeric = (rows[k + 1].x - rows[k - 1].x) / 0.001;
      EXPECT_NEAR(vx_numeric, rows[k].vx, j * 1e3 * 0.0005 * 0.0005 / 6 + 1e-3) << "t " << rows[k].t;
    }
  }
  EXPECT_NEAR(travelled, 100.0, 0.01);  // the trapezoidal rule's error at 2 kHz, well below 10 µm
}

TEST(CliPlan, ThesisYMotionEndsExactlyAndTriangleStaysOnItsEdges) {
  TempDir dir;
  ASSERT_EQ(run_cli("plan '" + (examples / "y_motion.gcode").string() + "' -o y.csv", dir.path()).exit_code, 0);
  const auto y = read_trajectory(dir / "y.csv");
  EXPECT_EQ(y.front().y, -75.0);
  EXPECT_EQ(y.back().y, 75.0);
  for (const auto& row : y) EXPECT_EQ(row.x, 222.132);

  ASSERT_EQ(run_cli("plan '" + (examples / "triangle.gcode").string() + "' -o tri.csv", dir.path()).exit_code, 0);
  const auto tri = read_trajectory(dir / "tri.csv");
  const double P[3][2] = {{187.132, -60}, {257.132, -60}, {222.132, 60}};
  for (const auto& row : tri) {  // G61: no blending, so every sample lies on an edge (to the 1 nm of the CSV)
    double nearest = INFINITY;
    for (int e = 0; e < 3; ++e) {
      const double *p = P[e], *q = P[(e + 1) % 3];
      const double dx = q[0] - p[0], dy = q[1] - p[1], len = std::hypot(dx, dy);
      const double s = std::clamp(((row.x - p[0]) * dx + (row.y - p[1]) * dy) / len, 0.0, len);
      nearest = std::min(nearest, std::hypot(row.x - p[0] - s * dx / len, row.y - p[1] - s * dy / len));
    }
    EXPECT_LT(nearest, 2e-6) << "t " << row.t;
  }
  EXPECT_EQ(tri.back().x, 187.132);
  EXPECT_EQ(tri.back().y, -60.0);
}

TEST(CliPlan, AccelJerkRateAndWorkOffsetFlags) {
  TempDir dir;
  write_text(dir / "work.gcode", "G0 X-50 Y0\nG1 X50 F60000\n");  // in work coordinates
  const CliResult r = run_cli("plan work.gcode --accel 2g --jerk 1000 --rate 1000 --work-offset-mm 222.132,0 -o w.csv --json",
                              dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = r.json();
  EXPECT_NEAR(s["peak_acceleration_m_s2"].get<double>(), 2 * g, 1e-9);
  EXPECT_NEAR(s["peak_jerk_m_s3"].get<double>(), 1000.0, 1e-9);
  EXPECT_NEAR(s["peak_velocity_m_s"].get<double>(), 1.0, 1e-12);
  const double T = rest_to_rest_s(0.1, 1.0, 2 * g, 1000.0);
  EXPECT_EQ(s["samples"].get<int>(), static_cast<int>(std::ceil(T * 1000)) + 1);
  const auto rows = read_trajectory(dir / "w.csv");
  EXPECT_EQ(rows.front().x, 172.132);
  EXPECT_EQ(rows.back().x, 272.132);
  EXPECT_DOUBLE_EQ(rows[1].t, 0.001);
}

TEST(CliPlan, BadProgramExitsWith2NamesTheWordAndLeavesNoFile) {
  TempDir dir;
  write_text(dir / "bad.gcode", "G0 X200 Y0\nM3 S100\nG1 X210 F600\nG41 X220\n");
  const CliResult r = run_cli("plan bad.gcode -o out.csv", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "error: bad.gcode:4:1: G41: cutter radius compensation is not supported\n");
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename().string().find("out.csv"), std::string::npos) << entry.path();  // no temp left
  }
  const CliResult missing = run_cli("plan nothing.gcode", dir.path());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(missing.err, "error: nothing.gcode: cannot open G-code file\n");
  const CliResult accel = run_cli("plan bad.gcode --accel 5furlongs", dir.path());
  EXPECT_EQ(accel.exit_code, 2);
  EXPECT_NE(accel.err.find("unknown unit 'furlongs'"), std::string::npos) << accel.err;
}

TEST(CliPlan, RealisticMarkingJobsStayWithinLimitsAndWorkspace) {
  for (const char* job : {"nameplate.gcode", "gear_outline.gcode"}) {
    TempDir dir;
    const CliResult r = run_cli("plan '" + (examples / job).string() + "' -o job.csv --json", dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto s = r.json();
    EXPECT_LE(s["peak_acceleration_m_s2"].get<double>(), 5 * g * (1 + 1e-9)) << job;
    EXPECT_LE(s["peak_jerk_m_s3"].get<double>(), 5 * g / 0.005 * (1 + 1e-9)) << job;
    EXPECT_GT(s["segments"].get<int>(), 500) << job;  // chords blended into chains of arcs
    const auto rows = read_trajectory(dir / "job.csv");
    for (const auto& row : rows) {
      ASSERT_GE(row.x, 172.132) << job;
      ASSERT_LE(row.x, 272.132) << job;
      ASSERT_LE(std::abs(row.y), 75.0) << job;
    }
    EXPECT_EQ(rows.back().x, 222.132) << job;  // both park at the workspace centre
    EXPECT_EQ(rows.back().y, 0.0) << job;
  }
}

}  // namespace
}  // namespace stiffpath::test
