// End-to-end tests of `stiffpath plan` on the examples: numbers in the CSV and JSON checked independently.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "gcode_corpus.hpp"
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

TEST(CliPlan, MalformedCorpusExits2WithEveryRefusalLocatedAndNoFileLeft) {
  const auto cases = read_corpus(fs::path(STIFFPATH_TEST_DATA_DIR) / "gcode_bad");
  ASSERT_GE(cases.size(), 50u);
  for (const auto& c : cases) {
    TempDir dir;
    std::string flags;
    for (const auto& flag : c.flags) flags += " " + flag;
    const CliResult r = run_cli("plan '" + c.path.string() + "'" + flags + " -o out.csv", dir.path());
    EXPECT_EQ(r.exit_code, 2) << c.path.filename();
    std::string expected;
    for (const auto& line : c.expected) expected += "error: " + line + "\n";
    EXPECT_EQ(r.err, expected) << c.path.filename();
    EXPECT_TRUE(fs::is_empty(dir.path())) << c.path.filename() << ": no output, no temporary file";
  }
}

TEST(CliPlan, WithJsonTheRefusalsAreOneDocumentOnStderr) {
  TempDir dir;
  const fs::path many = fs::path(STIFFPATH_TEST_DATA_DIR) / "gcode_bad" / "twenty_five_refusals.gcode";
  const CliResult r = run_cli("plan '" + many.string() + "' --json -o out.csv", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  const auto doc = nlohmann::json::parse(r.err);
  ASSERT_EQ(doc["errors"].size(), 20u);
  EXPECT_EQ(doc["omitted"].get<int>(), 5);
  EXPECT_EQ(doc["errors"][0]["file"].get<std::string>(), many.string());
  EXPECT_EQ(doc["errors"][0]["line"].get<int>(), 24);
  EXPECT_EQ(doc["errors"][19]["line"].get<int>(), 43);
  EXPECT_EQ(doc["errors"][0]["column"].get<int>(), 1);
  EXPECT_EQ(doc["errors"][0]["message"].get<std::string>(), "G41: cutter radius compensation is not supported");
  EXPECT_FALSE(fs::exists(dir / "out.csv"));

  const auto missing = nlohmann::json::parse(run_cli("plan nothing.gcode --json", dir.path()).err);
  EXPECT_EQ(missing["errors"][0]["file"].get<std::string>(), "nothing.gcode");
  EXPECT_TRUE(missing["errors"][0]["line"].is_null());
  write_text(dir / "ok.gcode", "G0 X200 Y0\nG1 X210 F600\n");
  const CliResult flag = run_cli("plan ok.gcode --jerk nan --json", dir.path());
  EXPECT_EQ(flag.exit_code, 2);
  const auto flag_doc = nlohmann::json::parse(flag.err);
  EXPECT_TRUE(flag_doc["errors"][0]["file"].is_null());
  EXPECT_EQ(flag_doc["errors"][0]["message"].get<std::string>(), "--jerk: must be within [1, 1e+08] m/s^3, got nan");
}

TEST(CliPlan, MaxSamplesRefusesAJobBeforeWritingAndNamesItsSize) {
  TempDir dir;
  write_text(dir / "dwell.gcode", "G0 X200 Y0\nG4 P10\n");  // 10 s: 20 001 samples at 2 kHz
  const CliResult refused = run_cli("plan dwell.gcode --max-samples 20000 -o out.csv", dir.path());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(refused.err,
            "error: dwell.gcode: the plan has 20001 samples (10.0 s at 2000 Hz, about 2.4 MB of CSV), more than the cap "
            "of 20000; raise it with --max-samples\n");
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
  const CliResult allowed = run_cli("plan dwell.gcode --max-samples 20001 -o out.csv --json", dir.path());
  ASSERT_EQ(allowed.exit_code, 0) << allowed.err;
  EXPECT_EQ(allowed.json()["samples"].get<int>(), 20001);
  // The default cap stops a day of motion at 1 mm/min (each block under the hour) before a sample is made.
  std::string slow = "G0 X200 Y0\n";
  for (int k = 0; k < 24; ++k) slow += k % 2 == 0 ? "G1 X250 F1\n" : "G1 X200 F1\n";
  write_text(dir / "slow.gcode", slow);
  const CliResult day = run_cli("plan slow.gcode -o slow.csv", dir.path());
  EXPECT_EQ(day.exit_code, 2);
  // 24 moves of 50 mm at 1/60 mm/s: 72 000 s at cruise (the lower bound), each at most L/v + v/a + a/j.
  const std::string head = "error: slow.gcode: the plan has ";
  ASSERT_EQ(day.err.rfind(head, 0), 0u) << day.err;
  const long samples = std::stol(day.err.substr(head.size()));
  EXPECT_GE(samples, 144'000'001);
  EXPECT_LE(samples, 144'000'001 + 24 * 2000 * (1.0 / 60 / 49033 + 0.005));
  EXPECT_NE(day.err.find("(72000.0 s at 2000 Hz, about 17.3 GB of CSV), more than the cap of 20000000; raise it with --max-samples"),
            std::string::npos)
      << day.err;
  EXPECT_FALSE(fs::exists(dir / "slow.csv"));
}

TEST(CliPlan, EveryNumericMotionFlagRefusesAbsurdValuesWithItsName) {
  TempDir dir;
  write_text(dir / "job.gcode", "G0 X200 Y0\nM3 S500\nG1 X210 F600\nM0\nG4 P0.1\n");
  const char* flags[] = {"--accel", "--jerk", "--max-velocity-mm-s", "--rate", "--blend-tolerance-mm",
                         "--junction-time-ms", "--s-max", "--program-stop", "--lookahead", "--max-samples",
                         "--work-offset-mm", "--start-mm"};
  const char* values[] = {"nan", "inf", "-inf", "0", "-1", "1e-300", "1e308"};
  for (const char* flag : flags) {
    for (const char* value : values) {
      const bool pair = std::string(flag) == "--work-offset-mm" || std::string(flag) == "--start-mm";
      const std::string arg = pair ? std::string(value) + ",0" : std::string(value);
      const CliResult r = run_cli(std::string("plan job.gcode --json ") + flag + "=" + arg, dir.path());
      SCOPED_TRACE(std::string(flag) + " " + arg);
      ASSERT_NE(r.exit_code, 1) << r.err;
      if (r.exit_code == 2) {
        // A start or offset the reader accepts can still put the job outside the robot's workspace:
        // then the refusal names the point instead of the flag.
        const bool moved_out = pair && r.err.find("outside robot oc-gu's workspace") != std::string::npos;
        EXPECT_TRUE(r.err.find(flag) != std::string::npos || moved_out) << r.err;
        continue;
      }
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const auto s = r.json();
      for (const char* key : {"duration_s", "peak_velocity_m_s", "peak_acceleration_m_s2", "peak_jerk_m_s3", "laser_on_s"}) {
        EXPECT_TRUE(std::isfinite(s[key].get<double>())) << key;
      }
      EXPECT_GE(s["samples"].get<int>(), 2);
    }
  }
}

TEST(CliPlan, RunTakesTheDialectFlagsAndPrintsTheWarnings) {
  TempDir dir;
  const fs::path marlin = fs::path(STIFFPATH_TEST_DATA_DIR) / "cam" / "marlin_laser.gcode";
  const std::string job = "run '" + marlin.string() + "' --work-offset-mm 182.132,-40 ";
  const CliResult ms = run_cli(job + "--dwell-p-units ms --json", dir.path());
  ASSERT_EQ(ms.exit_code, 0) << ms.err;
  EXPECT_EQ(ms.err, "warning: " + marlin.string() +
                        ":5: M106/M107 (Marlin's fan output) are read as laser on/off, M106 S 0-255 as the power (5 lines, "
                        "the first shown)\n");
  // The dwell was read in milliseconds: in seconds alone it would last 500 s (CliPlanCam checks both).
  EXPECT_LT(ms.json()["duration_s"].get<double>(), 20.0);
  const CliResult strict = run_cli(job + "--strict -o joints.csv", dir.path());
  EXPECT_EQ(strict.exit_code, 2);
  const std::string e = "error: " + marlin.string();
  EXPECT_EQ(strict.err, e + ":1:1: unexpected non-ASCII character\n" + e + ":5:1: M107: unsupported M code\n" + e +
                            ":8:1: M106: unsupported M code\n" + e + ":12:1: M107: unsupported M code\n" + e +
                            ":14:1: M106: unsupported M code\n" + e + ":17:1: M107: unsupported M code\n" + e +
                            ":19:1: unexpected non-ASCII character\n");  // the BOM, the fan words, the end-of-file character
  EXPECT_FALSE(fs::exists(dir / "joints.csv"));
}

TEST(CliPlan, ChordsFitRefitsTheGearsChordsAndAnUnknownChoiceIsRefused) {
  // --chords fit turns the gear's chains of chords into biarcs (about two pieces per chord), on the
  // same path within P: measured 3 859 segments against 2 468 blended, and the laser on for 6.72 s
  // against 6.48 s (these coarse chords run slower fitted, docs/motion.md).
  TempDir dir;
  const std::string gear = "plan '" + (examples / "gear_outline.gcode").string() + "' --json";
  const CliResult blend = run_cli(gear, dir.path()), fit = run_cli(gear + " --chords fit", dir.path());
  ASSERT_EQ(blend.exit_code, 0) << blend.err;
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const auto b = blend.json(), f = fit.json();
  EXPECT_GT(f["segments"].get<int>(), b["segments"].get<int>() * 5 / 4);
  EXPECT_NEAR(f["laser_on_s"].get<double>(), b["laser_on_s"].get<double>(), 0.08 * b["laser_on_s"].get<double>());
  EXPECT_LE(f["peak_acceleration_m_s2"].get<double>(), f["max_acceleration_m_s2"].get<double>() * (1 + 1e-9));
  const CliResult bad = run_cli(gear + " --chords spline", dir.path());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--chords"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("spline"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace stiffpath::test
