// A user's own asymmetric five-bar end to end: fit → cv → predict → run → simulate → experiment on its geometry and data.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "cli_runner.hpp"
#include "own_robot.hpp"

namespace stiffpath::test {
namespace {

const OwnRobot kRobot;
constexpr double kG = 9.80665;

// The robot file and the table of the known field in a fresh folder.
struct Workspace {
  TempDir dir;
  Workspace() {
    write_text(dir / "robot.json", kRobot.file("table.csv"));
    write_text(dir / "table.csv", table_of([](const V2& c) { return known_compliance(kRobot, c); }));
  }
  CliResult run(const std::string& args) const { return run_cli(args, dir.path()); }
};

// Points between the grid nodes (the grid lines are x = −60, −20, 20, 60 mm and y = 170, 210, 250 mm).
const std::vector<V2> kBetween = {{-0.040, 0.190}, {0.000, 0.230}, {0.040, 0.185}, {-0.052, 0.243}, {0.031, 0.201},
                                  {0.055, 0.172}};

std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.starts_with("#")) continue;  // a joint file's robot comment
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

TEST(CliOwnRobot, FitCvPredictRecoverTheKnownFieldBetweenTheNodes) {
  const Workspace w;
  const CliResult fit = w.run("fit --robot robot.json --method physical -o model.json --json");
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const auto doc = fit.json();
  EXPECT_EQ(doc["robot"]["name"], "asym");
  EXPECT_EQ(doc["robot"]["geometry"]["right_distal_mm"], 170.0);
  EXPECT_EQ(doc["robot"]["geometry"]["elbows"], nlohmann::json::array({1, -1}));
  EXPECT_EQ(doc["provenance"]["rows"], "");
  ASSERT_TRUE(std::filesystem::exists(w.dir / "model.json"));

  // predict: the fitted field against the known one at points between the nodes, under a force both ways.
  for (const V2& p : kBetween) {
    const V2 F(120.0, -80.0);
    const CliResult r = w.run(fmt::format("predict --robot robot.json --model model.json --x-mm {} --y-mm {} --fx-n 120 "
                                          "--fy-n -80 --json",
                                          p.x() * 1e3, p.y() * 1e3));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const V2 expected = known_compliance(kRobot, p) * F * 1e6;  // µm
    const V2 got(r.json()["dx_um"].get<double>(), r.json()["dy_um"].get<double>());
    // The table holds the field to 1 nm per cell (≈ 1e-5 of the 100 µm deflections).
    EXPECT_LT((got - expected).norm(), 1e-3 * expected.norm() + 0.01) << p.transpose() << ": " << got.transpose()
                                                                     << " vs " << expected.transpose();
  }

  // cv: the physical model predicts every held-out point; the bilinear one misses the curved field.
  const CliResult cv = w.run("cv --robot robot.json --json");
  ASSERT_EQ(cv.exit_code, 0) << cv.err;
  const auto report = cv.json();
  EXPECT_EQ(report["robot"], "asym");
  for (const auto& m : report["methods"]) {
    if (m["method"] == "physical") {
      EXPECT_EQ(m["predicted_points"], 12);
      EXPECT_LT(m["max_error_um"].get<double>(), 0.05);
    }
    if (m["method"] == "bilinear") {
      EXPECT_GT(m["mean_error_um"].get<double>(), 1.0);
    }
  }
  const std::string favoured = report["favoured_method"];
  EXPECT_TRUE(favoured == "physical" || favoured == "physical-2") << favoured;

  // fit without --method takes the method cross-validation favours and says so in the file.
  const CliResult automatic = w.run("fit --robot robot.json -o auto.json --json");
  ASSERT_EQ(automatic.exit_code, 0) << automatic.err;
  EXPECT_EQ(automatic.json()["method"], "physical");
  EXPECT_EQ(automatic.json()["provenance"]["method_selected_by"], "cross-validation");
  EXPECT_EQ(automatic.json()["provenance"]["selection"]["mean_error_um"].size(), 6U);
}

TEST(CliOwnRobot, RunCompensatesWithTheRobotsMassGeometryAndData) {
  const Workspace w;
  // A y line through the middle of the measured rectangle at 5 g.
  write_text(w.dir / "job.gcode", "G21 G90\nG0 X10 Y175\nM3 S100\nG1 Y245 F120000\nM5\n");
  const CliResult r = w.run("run job.gcode --robot robot.json --accel 5g -o joints.csv --json --compensation quasi-static --smooth-ms 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = r.json();
  EXPECT_EQ(s["robot"], "asym");
  EXPECT_EQ(s["samples_outside_grid"], 0);
  // The D'Alembert force is the robot's 2.2 kg times the planned 5 g.
  EXPECT_NEAR(s["peak_force_n"].get<double>(), 2.2 * 5 * kG, 1e-6);
  const auto rows = read_csv(w.dir / "joints.csv");
  ASSERT_GT(rows.size(), 100U);
  ASSERT_EQ(rows[0][1], "theta1_rad");
  const auto col = [&rows](const std::string& name) {
    return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  double checked = 0;
  for (std::size_t k = 1; k < rows.size(); k += 7) {
    const V2 p(std::stod(rows[k][col("x_mm")]) * 1e-3, std::stod(rows[k][col("y_mm")]) * 1e-3);
    const V2 cmd(std::stod(rows[k][col("xcmd_mm")]) * 1e-3, std::stod(rows[k][col("ycmd_mm")]) * 1e-3);
    const V2 F(std::stod(rows[k][col("fx_n")]), std::stod(rows[k][col("fy_n")]));
    // p_cmd = p − C(p)·F with the robot's own field (fitted from its table, so equal to the known one) …
    const V2 expected = p - known_compliance(kRobot, p) * F;
    EXPECT_LT((cmd - expected).norm(), 2e-9 + 2e-3 * (known_compliance(kRobot, p) * F).norm()) << k;
    // … and the joint angles are the robot's inverse kinematics of the corrected target.
    const V2 q = kRobot.joints(cmd);
    EXPECT_NEAR(std::stod(rows[k][1]), q.x(), 1e-8) << k;
    EXPECT_NEAR(std::stod(rows[k][2]), q.y(), 1e-8) << k;
    checked += F.norm() > 50 ? 1 : 0;
  }
  EXPECT_GT(checked, 5);
}

TEST(CliOwnRobot, G28GoesToTheRobotFilesHomeInPlanAndRun) {
  const Workspace w;
  std::string file = kRobot.file("table.csv");
  file.replace(file.find("\"moving_mass_kg\""), 0, "\"home_mm\": [-25, 195],\n  ");
  write_text(w.dir / "homed.json", file);
  write_text(w.dir / "park.gcode", "G21 G90\nG0 X10 Y230\nG28\n");
  const CliResult plan = w.run("plan park.gcode --robot homed.json -o traj.csv");
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  const auto traj = read_csv(w.dir / "traj.csv");
  ASSERT_EQ(traj[0][1], "x_mm");
  EXPECT_EQ(std::stod(traj.back()[1]), -25.0);
  EXPECT_EQ(std::stod(traj.back()[2]), 195.0);
  const CliResult run = w.run("run park.gcode --robot homed.json --no-compensation -o joints.csv");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto rows = read_csv(w.dir / "joints.csv");
  const V2 q = kRobot.joints({-0.025, 0.195});
  EXPECT_NEAR(std::stod(rows.back()[1]), q.x(), 1e-8);
  EXPECT_NEAR(std::stod(rows.back()[2]), q.y(), 1e-8);
  // Without home_mm, G28 is refused by both, naming the line.
  for (const char* cmd : {"plan", "run"}) {
    const CliResult r = w.run(std::string(cmd) + " park.gcode --robot robot.json");
    EXPECT_EQ(r.exit_code, 2) << cmd;
    EXPECT_EQ(r.err, "error: park.gcode:3:1: G28: the robot's home position is not set (home_mm in the robot file)\n") << cmd;
  }
}

TEST(CliOwnRobot, SimulateAndExperimentUseTheRobotsTwin) {
  const Workspace w;
  write_text(w.dir / "job.gcode", "G21 G90\nG0 X10 Y175\nM3 S100\nG1 Y245 F120000\nM5\n");
  ASSERT_EQ(w.run("run job.gcode --robot robot.json --accel 5g --format bin -o on.bin").exit_code, 0);
  ASSERT_EQ(w.run("run job.gcode --robot robot.json --accel 5g --format bin --no-compensation -o off.bin").exit_code, 0);
  const CliResult on = w.run("simulate on.bin --robot robot.json --json");
  const CliResult off = w.run("simulate off.bin --robot robot.json --json");
  ASSERT_EQ(on.exit_code, 0) << on.err;
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_EQ(on.json()["robot"], "asym");
  EXPECT_NEAR(on.json()["commanded_length_mm"].get<double>(), 70.0, 1e-6);
  // The tip lags by about m·a·C ≈ 2.2 kg · 49 N/kg · ~1 µm/N ≈ 0.1 mm: the peak deflection is of that order
  // (a twin built on the thesis's compliance at these coordinates would extrapolate past its singularity).
  const double peak = off.json()["peak_deflection_mm"].get<double>();
  EXPECT_GT(peak, 0.03);
  EXPECT_LT(peak, 0.5);
  EXPECT_LT(std::abs(on.json()["length_error_mm"].get<double>()), 0.3 * std::abs(off.json()["length_error_mm"].get<double>()));
  EXPECT_LT(on.json()["max_deviation_mm"].get<double>(), off.json()["max_deviation_mm"].get<double>());

  // experiment: the test motions placed in this robot's measured rectangle (120 × 80 mm).
  const CliResult e = w.run("experiment --robot robot.json --accelerations-g 5 -o out --no-plots");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto rows = read_csv(w.dir / "out" / "results.csv");
  ASSERT_EQ(rows.size(), 1U + 3 * 3);  // header, {without, thesis, default} × {x, y, triangle}
  double length[3][3] = {};
  for (std::size_t k = 1; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k][0], "asym");
    const int motion = rows[k][4] == "x" ? 0 : rows[k][4] == "y" ? 1 : 2;
    const double commanded = std::stod(rows[k][8]);
    if (motion == 0) {
      EXPECT_NEAR(commanded, 120.0, 1e-6);  // x ∈ [−60, 60] mm at y = 210 mm
    } else if (motion == 1) {
      EXPECT_NEAR(commanded, 80.0, 1e-6);  // y ∈ [170, 250] mm at x = 0
    }
    const int variant = rows[k][3] == "0" ? 0 : rows[k].back() == "thesis" ? 1 : 2;
    length[variant][motion] = std::abs(std::stod(rows[k][9]));
  }
  for (int variant = 1; variant < 3; ++variant) {
    for (int motion = 0; motion < 3; ++motion) {
      EXPECT_LT(length[variant][motion], 0.5 * length[0][motion]) << variant << ' ' << motion;
    }
  }
}

// The robot file's tip_damping_ratio is the ζ that run's dynamic compensation and the twin's plant assume:
// a file with ζ = 0.15 gives what --damping-ratio 0.15 gives with a file without it, and the flag wins.
TEST(CliOwnRobot, TheRobotFilesDampingRatioIsWhatRunAndTheTwinAssume) {
  const Workspace w;
  std::string text = kRobot.file("table.csv");
  const std::string mass = "\"moving_mass_kg\": 2.2,";
  ASSERT_NE(text.find(mass), std::string::npos);
  write_text(w.dir / "damped.json", std::string(text).replace(text.find(mass), mass.size(), mass + " \"tip_damping_ratio\": 0.15,"));
  write_text(w.dir / "bad.json", std::string(text).replace(text.find(mass), mass.size(), mass + "\n  \"tip_damping_ratio\": 1.5,"));
  write_text(w.dir / "job.gcode", "G21 G90\nG0 X10 Y175\nM3 S100\nG1 Y245 F120000\nG1 X-30\nM5\n");
  const auto run = [&](const std::string& robot, const std::string& extra, const std::string& out) {
    const CliResult r = w.run("run job.gcode --robot " + robot + " --accel 5g --json -o " + out + " " + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.json()["damping_ratio"].get<double>();
  };
  EXPECT_EQ(run("robot.json", "", "plain.csv"), 0.05);
  EXPECT_EQ(run("damped.json", "", "damped.csv"), 0.15);
  EXPECT_EQ(run("robot.json", "--damping-ratio 0.15", "flag.csv"), 0.15);
  EXPECT_EQ(run("damped.json", "--damping-ratio 0.3", "both.csv"), 0.3);
  const auto damped = read_csv(w.dir / "damped.csv"), flag = read_csv(w.dir / "flag.csv"), plain = read_csv(w.dir / "plain.csv");
  ASSERT_GT(damped.size(), 100U);
  EXPECT_EQ(damped, flag);
  EXPECT_NE(damped, plain);  // the dynamic inversion's lag depends on ζ

  // The twin's plant: the same commands ring down differently on a plant of the file's ζ.
  ASSERT_EQ(w.run("run job.gcode --robot robot.json --accel 5g --format bin -o on.bin").exit_code, 0);
  const auto residual = [&](const std::string& robot, const std::string& extra) {
    const CliResult r = w.run("simulate on.bin --json --robot " + robot + " " + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.json()["residual_vibration_mm"].get<double>();
  };
  const double file_zeta = residual("damped.json", ""), flag_zeta = residual("robot.json", "--damping-ratio 0.15");
  EXPECT_EQ(file_zeta, flag_zeta);
  EXPECT_NE(file_zeta, residual("robot.json", ""));

  // 1.5 is not an underdamped mode: the file, its line and the value.
  const CliResult bad = w.run("run job.gcode --robot bad.json -o bad.csv");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.json:"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("tip_damping_ratio"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("1.5"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(w.dir / "bad.csv"));
}

TEST(CliOwnRobot, DataCheckAndTheExperimentOnAUsersOwnPath) {
  const Workspace w;
  // The robot is not its own mirror image: no symmetry is expected of its data; the exact field is linear.
  const CliResult check = w.run("data check --robot robot.json --json");
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_EQ(check.json()["flagged"], 0);
  EXPECT_TRUE(check.json()["symmetry"].empty());
  EXPECT_EQ(check.json()["linearity"].size(), 12U * 2 * 2);  // dx, dy of 12 points × 2 directions
  // A closed square of the user's as the only path of the experiment.
  write_text(w.dir / "square.gcode",
             "G21 G90\nG61\nG0 X-30 Y180\nM3 S100\nG1 X30 Y180 F120000\nG1 X30 Y240\nG1 X-30 Y240\nG1 X-30 Y180\nM5\n");
  const CliResult e = w.run("experiment --robot robot.json --path square.gcode:4 --accelerations-g 3 --variants thesis -o out "
                            "--no-plots");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto rows = read_csv(w.dir / "out" / "results.csv");
  ASSERT_EQ(rows.size(), 3U);
  for (std::size_t k = 1; k < 3; ++k) {
    EXPECT_EQ(rows[k][4], "square");
    EXPECT_NEAR(std::stod(rows[k][8]), 240.0, 1e-6);  // the commanded length of four 60 mm sides
  }
  EXPECT_LT(std::stod(rows[2][11]), std::stod(rows[1][11]));  // compensation lowers the largest deviation
}

TEST(CliOwnRobot, AFieldBeyondThePhysicalModelIsApproximatedWithinFivePercent) {
  // A compliant base frame adds a constant C_b to every point: C = U⁻ᵀDU⁻¹ + C_b is not of the model's
  // form with a linear D (Uᵀ C_b U varies with the geometry), so the fit can only approximate it.
  TempDir dir;
  M2 base;
  base << 0.25e-6, 0.05e-6, 0.05e-6, 0.35e-6;
  const auto field = [&](const V2& c) { return M2(known_compliance(kRobot, c) + base); };
  write_text(dir / "robot.json", kRobot.file("table.csv"));
  write_text(dir / "table.csv", table_of(field));
  ASSERT_EQ(run_cli("fit --robot robot.json --method physical -o m.json", dir.path()).exit_code, 0);
  double worst = 0;
  for (const V2& p : kBetween) {
    for (const V2& F : {V2(150.0, 0.0), V2(0.0, -150.0), V2(100.0, 100.0)}) {
      const CliResult r = run_cli(fmt::format("predict --robot robot.json --model m.json --x-mm {} --y-mm {} --fx-n {} "
                                              "--fy-n {} --json",
                                              p.x() * 1e3, p.y() * 1e3, F.x(), F.y()),
                                  dir.path());
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const V2 expected = field(p) * F * 1e6;
      const V2 got(r.json()["dx_um"].get<double>(), r.json()["dy_um"].get<double>());
      worst = std::max(worst, (got - expected).norm() / expected.norm());
    }
  }
  // The acceptance tolerance: 5 % of the deflection, a fifth of what compensating at all removes.
  EXPECT_LT(worst, 0.05);
  EXPECT_GT(worst, 1e-4);  // and it is an approximation, not the exact case above
  std::printf("base-frame field: largest relative error of the physical fit between the nodes %.2f %%\n", worst * 100);
}

}  // namespace
}  // namespace stiffpath::test
