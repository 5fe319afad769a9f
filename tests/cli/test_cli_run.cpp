// End-to-end tests of `stiffpath run`: the thesis's y motion checked against an independent computation,
// compensation switches, acceleration sources, output formats and refusals that leave no file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cli_runner.hpp"
#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::test {
namespace {

const std::string kExamples = std::string(STIFFPATH_SOURCE_DIR) + "/examples/";

struct Row {
  double t, th1, th2, x, y, xcmd, ycmd, fx, fy;
  int line, laser;
};

std::vector<Row> read_rows(const std::filesystem::path& path) {
  core::CsvReader csv(path.string());
  std::vector<Row> rows;
  const auto c = [&](const char* n) { return csv.column(n); };
  const std::size_t t = c("t_s"), a = c("theta1_rad"), b = c("theta2_rad"), x = c("x_mm"), y = c("y_mm"),
                    xc = c("xcmd_mm"), yc = c("ycmd_mm"), fx = c("fx_n"), fy = c("fy_n"), l = c("line"), la = c("laser");
  while (csv.next()) {
    rows.push_back({csv.number(t), csv.number(a), csv.number(b), csv.number(x), csv.number(y), csv.number(xc),
                    csv.number(yc), csv.number(fx), csv.number(fy), static_cast<int>(csv.integer(l)),
                    static_cast<int>(csv.integer(la))});
  }
  return rows;
}

// These three compare the thesis's method (quasi-static, unsmoothed) with independent computations.
TEST(CliRun, YMotionMatchesAnIndependentComputation) {
  TempDir dir;
  const CliResult plan = run_cli("plan " + kExamples + "y_motion.gcode --accel 5g -o traj.csv", dir.path());
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  const CliResult run = run_cli("run " + kExamples + "y_motion.gcode --accel 5g -o joints.csv --json --compensation quasi-static --smooth-ms 0 --model thesis-oc", dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;

  // The thesis's per-point fits at x2y1 … x2y5 (the y motion runs along x = 222.132 mm, the grid's
  // middle column, so eq. 4.12 reduces to linear interpolation in y between those five points).
  const auto fits = compliance::fit_points(measurement::load_displacement_table(measurement::thesis_dataset()).filter("OC"));
  std::vector<compliance::PointFit> column;
  for (const auto& f : fits) {
    if (std::abs(f.position.x() - 0.222132) < 1e-9) column.push_back(f);
  }
  ASSERT_EQ(column.size(), 5u);

  core::CsvReader traj((dir / "traj.csv").string());
  const auto ty = traj.column("y_mm"), tax = traj.column("ax_mm_s2"), tay = traj.column("ay_mm_s2");
  const auto rows = read_rows(dir / "joints.csv");
  std::size_t k = 0;
  double peak_correction_um = 0.0;
  while (traj.next()) {
    ASSERT_LT(k, rows.size());
    const Row& r = rows[k++];
    const double y = traj.number(ty) * 1e-3;
    const double fx = -3.6 * traj.number(tax) * 1e-3, fy = -3.6 * traj.number(tay) * 1e-3;
    EXPECT_NEAR(r.fx, fx, 1e-3);
    EXPECT_NEAR(r.fy, fy, 1e-3);
    std::size_t j = 0;
    while (j + 2 < column.size() && y > column[j + 1].position.y()) ++j;
    const double w = (y - column[j].position.y()) / (column[j + 1].position.y() - column[j].position.y());
    const compliance::Mat2 C = (1 - w) * column[j].compliance() + w * column[j + 1].compliance();
    const double dx = C(0, 0) * fx + C(0, 1) * fy, dy = C(1, 0) * fx + C(1, 1) * fy;
    EXPECT_NEAR(r.xcmd, 222.132 - dx * 1e3, 2e-6);  // mm; the file keeps 6 decimals
    EXPECT_NEAR(r.ycmd, y * 1e3 - dy * 1e3, 2e-6);
    peak_correction_um = std::max(peak_correction_um, std::hypot(dx, dy) * 1e6);
    // Eq. 2.2 on the corrected target.
    const double xc = r.xcmd * 1e-3, yc = r.ycmd * 1e-3;
    const double phi = std::atan2(yc, xc), eta = std::acos(std::hypot(xc, yc) / 0.3);
    EXPECT_NEAR(r.th1, phi + eta, 2e-8);
    EXPECT_NEAR(r.th2, phi - eta, 2e-8);
  }
  EXPECT_EQ(k, rows.size());
  const auto summary = run.json();
  EXPECT_EQ(summary["samples"].get<std::size_t>(), rows.size());
  EXPECT_NEAR(summary["peak_correction_um"].get<double>(), peak_correction_um, 0.01);
  EXPECT_GT(peak_correction_um, 300.0);  // ~480 µm at the stretched-out end under 5 g
}

TEST(CliRun, NoCompensationAndGainZeroGiveTheSameJointsAndTheCorrectionScalesWithGain) {
  TempDir dir;
  const std::string job = kExamples + "triangle.gcode";
  ASSERT_EQ(run_cli("run " + job + " --no-compensation -o a.csv --compensation quasi-static --smooth-ms 0", dir.path()).exit_code, 0);
  ASSERT_EQ(run_cli("run " + job + " --gain 0 -o b.csv --compensation quasi-static --smooth-ms 0", dir.path()).exit_code, 0);
  const CliResult half = run_cli("run " + job + " --gain 0.5 --json --compensation quasi-static --smooth-ms 0", dir.path());
  const CliResult full = run_cli("run " + job + " --json --compensation quasi-static --smooth-ms 0", dir.path());
  const auto a = read_rows(dir / "a.csv"), b = read_rows(dir / "b.csv");
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].th1, b[k].th1);
    ASSERT_EQ(a[k].xcmd, a[k].x);
  }
  EXPECT_NEAR(half.json()["peak_correction_um"].get<double>(), 0.5 * full.json()["peak_correction_um"].get<double>(),
              1e-6);
  EXPECT_EQ(full.json()["peak_deflection_um"], half.json()["peak_deflection_um"]);
}

TEST(CliRun, NumericAndAnalyticAccelerationAgreeWithinTheDiscretisationError) {
  TempDir dir;
  const std::string job = kExamples + "y_motion.gcode --accel 5g";
  ASSERT_EQ(run_cli("run " + job + " -o analytic.csv --compensation quasi-static --smooth-ms 0", dir.path()).exit_code, 0);
  ASSERT_EQ(run_cli("run " + job + " --accel-source numeric -o numeric.csv --compensation quasi-static --smooth-ms 0", dir.path()).exit_code, 0);
  const auto a = read_rows(dir / "analytic.csv"), n = read_rows(dir / "numeric.csv");
  ASSERT_EQ(a.size(), n.size());
  // The central difference of a piecewise-cubic position is exact inside a phase; across a jerk step Δj
  // it errs by at most |Δj|·Δt/6. With j = 5 g / 5 ms and steps of up to 2j: 2·9806.65·0.0005/6 m/s².
  const double bound_N = 3.6 * 2 * 9806.65 * 0.0005 / 6.0 + 1e-3;
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    worst = std::max(worst, std::hypot(a[k].fx - n[k].fx, a[k].fy - n[k].fy));
    EXPECT_EQ(a[k].t, n[k].t);
  }
  EXPECT_LE(worst, bound_N);
  EXPECT_GT(worst, 0.1 * bound_N);  // the two sources do differ near the switches
}

TEST(CliRun, BinaryOutputHoldsTheSameCommands) {
  TempDir dir;
  const std::string job = kExamples + "x_motion.gcode";
  ASSERT_EQ(run_cli("run " + job + " -o j.csv", dir.path()).exit_code, 0);
  ASSERT_EQ(run_cli("run " + job + " -o j.bin --format bin", dir.path()).exit_code, 0);
  const auto rows = read_rows(dir / "j.csv");
  EXPECT_EQ(std::filesystem::file_size(dir / "j.bin"), 128u + 120u * rows.size());  // binary version 2
}

TEST(CliRun, LeavingTheWorkspaceFailsNamingTimeLineAndQuantityAndLeavesNoFile) {
  TempDir dir;
  write_text(dir / "far.gcode", "G21 G90\nG0 X222 Y0\nM3 S100\nG1 X296 F60000\nM5\n");
  // By default the job stops where it leaves the compliance model's measured region (x ≤ 272.132 mm) …
  const CliResult outside = run_cli("run far.gcode -o out.csv", dir.path());
  EXPECT_EQ(outside.exit_code, 2);
  EXPECT_NE(outside.err.find("far.gcode:4: t = "), std::string::npos) << outside.err;
  EXPECT_NE(outside.err.find("is more than 1 mm outside the compliance model's measured region x [172.132, 272.132] mm"),
            std::string::npos)
      << outside.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
  // … and when told to clamp, where the corrected target leaves the workspace.
  const CliResult r = run_cli("run far.gcode --outside clamp -o out.csv", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("far.gcode:4: t = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("is not reachable: too close to the stretched-out singularity: the left arm would reach"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()) || !std::filesystem::exists(dir / "out.csv"));
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
  }
}

TEST(CliRun, JointVelocityLimitIsReportedWithItsValue) {
  TempDir dir;
  // A user mechanism with a low joint speed limit: the 5 g y motion needs about 10 rad/s.
  const CliResult show = run_cli("mechanism show oc-gu --json");
  auto doc = show.json();
  doc["joints"][0]["max_velocity_rad_s"] = 5.0;
  write_text(dir / "slow.json", doc.dump());
  const CliResult r = run_cli("run " + kExamples + "y_motion.gcode --mechanism slow.json -o out.csv", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("y_motion.gcode:7: t = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("joint theta1 velocity"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("exceeds the limit 5.00 rad/s"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
}

TEST(CliRun, MirroredTrianglesGiveNearlyMirroredCorrectionsOnOc) {
  // OC is symmetric about y = 0 by design; its measured model is only as symmetric as the data
  // (the thesis validates its procedure by this symmetry within the arm's ±23 µm).
  TempDir dir;
  write_text(dir / "up.gcode", "G21 G90 G61\nG0 X190 Y10\nM3 S1\nG1 X250 Y60 F60000\nG1 X250 Y10\nG1 X190 Y10\nM5\n");
  write_text(dir / "down.gcode", "G21 G90 G61\nG0 X190 Y-10\nM3 S1\nG1 X250 Y-60 F60000\nG1 X250 Y-10\nG1 X190 Y-10\nM5\n");
  ASSERT_EQ(run_cli("run up.gcode -o up.csv", dir.path()).exit_code, 0);
  ASSERT_EQ(run_cli("run down.gcode -o down.csv", dir.path()).exit_code, 0);
  const auto u = read_rows(dir / "up.csv"), d = read_rows(dir / "down.csv");
  ASSERT_EQ(u.size(), d.size());
  double worst = 0.0, largest = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    const double cx_u = u[k].xcmd - u[k].x, cy_u = u[k].ycmd - u[k].y;
    const double cx_d = d[k].xcmd - d[k].x, cy_d = d[k].ycmd - d[k].y;
    worst = std::max(worst, std::hypot(cx_u - cx_d, cy_u + cy_d) * 1e3);
    largest = std::max(largest, std::hypot(cx_u, cy_u) * 1e3);
  }
  EXPECT_GT(largest, 100.0);  // µm
  EXPECT_LT(worst, 0.25 * largest);
}

}  // namespace
}  // namespace stiffpath::test
