// `campaign plan → simulate → measure → fit → score` for a robot of one's own, step 0 from its own data, and the bands of predict and cv.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.hpp"

namespace stiffpath::test {
namespace {

const std::string kRobot = STIFFPATH_SOURCE_DIR "/examples/robots/asym_5bar.json";
constexpr const char* kField =
    "actuator_rad_per_Nm=4e-5/6e-5,proximal_bending_per_Nm2=2e-4,distal_axial_m_per_N=1e-7,base_x_m_per_N=2e-7";

// The F_N column of a displacement table, in file order.
std::vector<double> forces_of(const std::filesystem::path& table) {
  std::ifstream in(table);
  std::string line;
  std::getline(in, line);
  std::size_t column = 0;
  for (std::size_t pos = 0, k = 0;; ++k) {
    const std::size_t comma = line.find(',', pos);
    if (line.substr(pos, comma - pos) == "F_N") column = k;
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  std::vector<double> out;
  while (std::getline(in, line)) {
    std::size_t pos = 0;
    for (std::size_t k = 0; k < column; ++k) pos = line.find(',', pos) + 1;
    out.push_back(std::stod(line.substr(pos)));
  }
  return out;
}

TEST(CliCampaignPlan, ATableWithoutForceKgfGetsNoWireHookAtStepZero) {
  // The example robot's table gives F_N only: step 0 carries nothing, so measuring the simulated campaign gives
  // back exactly the table's forces (with another robot's 0.110 kgf hook, 50 N would come back as 48.92 N).
  TempDir dir;
  const CliResult sim = run_cli("campaign simulate --robot " + kRobot + " --noise-sigma-um 0 -o c.csv --json", dir.path());
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  EXPECT_EQ(sim.json()["step0_kgf"].get<double>(), 0.0);
  ASSERT_EQ(run_cli("measure c.csv --robot " + kRobot + " -o m.csv", dir.path()).exit_code, 0);
  const auto measured = forces_of(dir / "m.csv");
  ASSERT_FALSE(measured.empty());
  for (const double f : measured) EXPECT_NEAR(std::remainder(f, 50.0), 0.0, 1e-6) << f;  // 50, 100, 150, 200 N
}

TEST(CliCampaignPlan, APlannedCampaignRehearsedOnAKnownFieldIsMeasuredFittedAndScored) {
  TempDir dir;
  const auto run = [&](const std::string& args) { return run_cli(args, dir.path()); };
  const CliResult plan = run("campaign plan --robot " + kRobot + " --points 9 --region-mm -60 60 170 250 -o plan.csv --json");
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  const auto p = plan.json();
  EXPECT_EQ(p["points_mm"].size(), 9u);
  EXPECT_EQ(p["loads_N"], nlohmann::json::parse("[50.0, 150.0, 200.0]"));  // the table's loads, spread
  EXPECT_EQ(p["directions"], nlohmann::json::parse(R"(["+x", "-y"])"));    // the table's directions
  EXPECT_LT(p["interpolation_variance_vs_grid"].get<double>() + p["physical_variance_vs_grid"].get<double>(), 2.0);
  const CliResult sim = run("campaign simulate --robot " + kRobot + " --plan plan.csv --field-terms '" + kField +
                            "' --seed 4 -o c.csv --truth-output t.csv");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  ASSERT_EQ(run("measure c.csv --robot " + kRobot + " -o m.csv").exit_code, 0);
  ASSERT_EQ(run("fit m.csv --robot " + kRobot + " --method physical-spline -o model.json").exit_code, 0);
  const CliResult score = run("campaign score --robot " + kRobot + " --model model.json --field-terms '" + kField +
                              "' --force-n 100 --json");
  ASSERT_EQ(score.exit_code, 0) << score.err;
  // Nine points with the arm's noise recover this field to about the noise (measured: 11-15 µm RMS at 100 N).
  EXPECT_LT(score.json()["rms_um"].get<double>(), 25.0);
  EXPECT_GT(score.json()["rms_um"].get<double>(), 1.0);
  // The model file carries its uncertainty, and predict states the band.
  const CliResult pred = run("predict --robot " + kRobot + " --model model.json --x-mm 0 --y-mm 210 --fx-n 100 --fy-n 0 --json");
  ASSERT_EQ(pred.exit_code, 0) << pred.err;
  EXPECT_GT(pred.json()["dx_band_95_um"].get<double>(), 0.0);
  EXPECT_GT(pred.json()["measured_dx_band_95_um"].get<double>(), pred.json()["dx_band_95_um"].get<double>());
  // Bad terms and a plan without a field are refused with the reason.
  const CliResult bad = run("campaign simulate --robot " + kRobot + " --plan plan.csv --field-terms 'actuator=1' -o x.csv");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("unknown name"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.csv"));
  const CliResult none = run("campaign simulate --robot " + kRobot + " --plan plan.csv -o x.csv");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("give the known field"), std::string::npos) << none.err;
}

TEST(CliCampaignPlan, CvReportsTheBandsCalibration) {
  const CliResult cv = run_cli("cv --robot oc-gu --json");
  ASSERT_EQ(cv.exit_code, 0) << cv.err;
  for (const auto& m : cv.json()["methods"]) {
    const auto& band = m["band_95"];
    EXPECT_GT(band["cells"].get<int>(), 40) << m["method"];
    EXPECT_GE(band["fraction"].get<double>(), 0.85) << m["method"];
    EXPECT_GT(band["mean_half_width_um"].get<double>(), 0.0) << m["method"];
  }
}

}  // namespace
}  // namespace stiffpath::test
