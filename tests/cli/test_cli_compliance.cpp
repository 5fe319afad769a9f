// End-to-end tests of `stiffpath fit`, `predict`, `cv` and `plot`: numbers, files and errors.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_runner.hpp"

namespace stiffpath::test {
namespace {

TEST(CliCompliance, FitThenPredictMatchesTheBuiltInModel) {
  TempDir dir;
  const CliResult fit = run_cli("fit --robot oc-gu --method bilinear -o model.json", dir.path());
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  ASSERT_TRUE(std::filesystem::exists(dir / "model.json"));
  const CliResult a = run_cli("predict --model model.json --x-mm 200 --y-mm 20 --fx-n 120 --fy-n -60 --json", dir.path());
  const CliResult b = run_cli("predict --model thesis-oc --x-mm 200 --y-mm 20 --fx-n 120 --fy-n -60 --json");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NEAR(a.json()["dx_um"].get<double>(), b.json()["dx_um"].get<double>(), 1e-6);
  EXPECT_NEAR(a.json()["dy_um"].get<double>(), b.json()["dy_um"].get<double>(), 1e-6);
  // dx = Cxx·Fx + Cxy·Fy with the printed matrix.
  const auto c = a.json()["C_um_per_N"];
  EXPECT_NEAR(a.json()["dx_um"].get<double>(), c[0][0].get<double>() * 120 - c[0][1].get<double>() * 60, 1e-6);
}

TEST(CliCompliance, PredictAtAGridPointReproducesTheThesisTable) {
  // OC x3y5 under −y at the 250 N step (F_N = 242.71 N): table 2.3 gives Δy = −1.671 mm. The relative
  // bilinear prediction is the fitted slope times the force: within the fit's residual (~10 µm).
  const CliResult r = run_cli("predict --model thesis-oc --x-mm 272.132 --y-mm 75 --fx-n 0 --fy-n -242.71 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(r.json()["dy_um"].get<double>(), -1671.0, 15.0);
  EXPECT_TRUE(r.json()["inside_grid"].get<bool>());
}

TEST(CliCompliance, CvReportsTheIssueNumbers) {
  const CliResult r = run_cli("cv thesis --robot oc-gu --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.json()["rows"], "OC");
  EXPECT_TRUE(r.json()["could_not_run"].empty());
  const auto methods = r.json()["methods"];
  ASSERT_EQ(methods.size(), 6u);
  EXPECT_EQ(methods[0]["method"], "bilinear");
  EXPECT_NEAR(methods[0]["interior_mean_error_um"].get<double>(), 90.0, 5.0);
  EXPECT_EQ(methods[3]["method"], "physical");
  EXPECT_LT(methods[3]["interior_mean_error_um"].get<double>(), 25.0);
  EXPECT_EQ(methods[5]["method"], "physical-spline");
  EXPECT_LT(methods[5]["mean_error_um"].get<double>(), 0.8 * methods[3]["mean_error_um"].get<double>());
  EXPECT_EQ(r.json()["favoured_method"], "physical-spline");
}

TEST(CliCompliance, ErrorsAreNamedAndLeaveNoFile) {
  TempDir dir;
  write_text(dir / "bad.csv",
             "mechanism,direction,point,x_mm,y_mm,step,force_kgf,F_N,F_nominal_N,dx_mm,dy_mm,dz_mm,rx_deg,ry_deg\n"
             "OC,+x,x1y1,172.132,-75,1,5,47.95,50,0.1,abc,,,\n");
  const CliResult r = run_cli("fit bad.csv --robot oc-gu -o m.json", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.csv:2:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("column 'dy_mm': 'abc' is not a finite number"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "m.json"));
  const CliResult m = run_cli("fit --robot oc-gu --method kriging -o m.json", dir.path());
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_NE(m.err.find("--method: compliance method must be auto, bilinear, symmetric, physical, physical-0, physical-2 or "
                       "physical-spline, got 'kriging'"),
            std::string::npos)
      << m.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "m.json"));
  write_text(dir / "broken.json", "{\"format\": \"stiffpath-compliance-model\",\n \"version\": 1,\n \"method\": 3}");
  const CliResult b = run_cli("predict --model broken.json --x-mm 200 --y-mm 0 --fx-n 1 --fy-n 0", dir.path());
  EXPECT_EQ(b.exit_code, 2);
  EXPECT_EQ(b.err, "error: broken.json:3:2: method: must be a string, got number 3\n");
}

TEST(CliCompliance, OutsidePolicyErrorRefusesPointsOffTheGrid) {
  TempDir dir;
  ASSERT_EQ(run_cli("fit --robot sc-gu --outside error -o m.json", dir.path()).exit_code, 0);
  const CliResult r = run_cli("predict --robot sc-gu --model m.json --x-mm 290 --y-mm 0 --fx-n 10 --fy-n 0", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is more than 1 mm outside the measured region of model m.json, x [172.132, 272.132] mm"),
            std::string::npos)
      << r.err;
  // Within the 1 mm margin the model clamps; --outside clamp goes on anywhere.
  EXPECT_EQ(run_cli("predict --robot sc-gu --model m.json --x-mm 273 --y-mm 0 --fx-n 10 --fy-n 0", dir.path()).exit_code, 0);
  EXPECT_EQ(run_cli("predict --robot sc-gu --model m.json --x-mm 290 --y-mm 0 --fx-n 10 --fy-n 0 --outside clamp",
                    dir.path()).exit_code,
            0);
}

TEST(CliCompliance, PlotsWriteSvgAndPng) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  TempDir dir;
  const CliResult r = run_cli("plot compliance --model thesis-sc -o figs", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(std::filesystem::file_size(dir / "figs" / "compliance_thesis-sc.png"), 10000u);
  EXPECT_GT(std::filesystem::file_size(dir / "figs" / "compliance_thesis-sc.svg"), 10000u);
  for (const auto& entry : std::filesystem::directory_iterator(dir / "figs")) {
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  }
}

}  // namespace
}  // namespace stiffpath::test
