// End-to-end tests of `campaign simulate`, `measure`, `data check` and `repeatability`: numbers, files, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cli_runner.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::test {
namespace {

const std::string kData = STIFFPATH_TEST_DATA_DIR;

TEST(CliMeasure, SimulateThenMeasureRecoversTheTruthWithinTheNoise) {
  TempDir dir;
  const CliResult sim =
      run_cli("campaign simulate --mechanism sc-gu --readings 2 --seed 11 -o camp.csv --truth-output truth.csv --json",
              dir.path());
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  EXPECT_EQ(sim.json()["readings"].get<int>(), 30 * 6 * 2);
  const CliResult m = run_cli("measure camp.csv --mechanism sc-gu -o table.csv --json", dir.path());
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(m.json()["rows"].get<int>(), 150);
  EXPECT_EQ(m.json()["robot_rows"], "SC");
  EXPECT_EQ(m.json()["rows_with_spread"].get<int>(), 150);
  const auto truth = measurement::load_displacement_table((dir / "truth.csv").string());
  const auto got = measurement::load_displacement_table((dir / "table.csv").string());
  ASSERT_EQ(got.rows.size(), truth.rows.size());
  // σ of a recovered displacement: 11.5 µm · √((91/160)² + (69/160)²) · √(1/2 + 1/2) = 8.2 µm; allow 5σ.
  const double sigma_d = 11.5e-6 * std::hypot(91.0 / 160.0, 69.0 / 160.0);
  double worst = 0.0;
  for (std::size_t i = 0; i < got.rows.size(); ++i) {
    EXPECT_EQ(got.rows[i].mechanism, "SC");
    EXPECT_NEAR(got.rows[i].force_N, truth.rows[i].force_N, 1e-3);
    worst = std::max({worst, std::abs(*got.rows[i].dx_m - *truth.rows[i].dx_m),
                      std::abs(*got.rows[i].dy_m - *truth.rows[i].dy_m)});
  }
  EXPECT_LT(worst, 5.0 * sigma_d);
  EXPECT_GT(worst, 0.5 * sigma_d);  // the noise is really there
  // The largest total is SC x3y5 under −y at 250 N (3.33 mm in the thesis's text).
  EXPECT_NEAR(m.json()["max_total_displacement_mm"].get<double>(), 3.3, 0.1);
}

TEST(CliMeasure, HandComputedCampaignAndNominalForces) {
  TempDir dir;
  const CliResult m = run_cli("measure '" + kData + "/campaign_hand.csv' -o t.csv", dir.path());
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_NE(m.out.find("4 readings -> 2 rows"), std::string::npos) << m.out;
  const auto t = measurement::load_displacement_table((dir / "t.csv").string());
  EXPECT_NEAR(*t.rows[0].dx_m, 0.091e-3, 1e-9);
  EXPECT_NEAR(t.rows[1].force_N, (9.92 - 0.11) * 9.80665, 1e-4);
  // Nominal loads are the campaign's own: a campaign without a force_nominal_N column needs the step's load.
  const CliResult refused = run_cli("measure '" + kData + "/campaign_hand.csv' --nominal-forces -o n.csv", dir.path());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "n.csv"));
  ASSERT_EQ(run_cli("measure '" + kData + "/campaign_hand.csv' --nominal-forces --nominal-step-N 50 -o n.csv", dir.path()).exit_code, 0);
  const auto n = measurement::load_displacement_table((dir / "n.csv").string());
  EXPECT_DOUBLE_EQ(n.rows[1].force_N, 100.0);
  EXPECT_DOUBLE_EQ(n.rows[1].force_kgf, 9.92);
}

TEST(CliMeasure, BadCampaignExits2WithLocationAndWritesNothing) {
  TempDir dir;
  write_text(dir / "c.csv",
             "point,x_mm,y_mm,direction,step,force_kgf,Ux_mm,Uy_mm,Uz_mm,Lx_mm,Ly_mm,Lz_mm\n"
             "P,200,0,+x,1,5,200,0,160,200,0,0\nP,200,0,+x,2,9.92,200,0,160,200,0,0\n");
  const CliResult r = run_cli("measure c.csv -o out.csv", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error: c.csv:2: column 'step': point P, direction +x: step 0"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);  // no temporary left either
}

TEST(CliDataCheck, ThesisFiguresAndNominalForceEffect) {
  const CliResult r = run_cli("data check thesis --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = r.json();
  EXPECT_EQ(j["accuracy_um"].get<double>(), 23.0);
  EXPECT_NEAR(j["angle_accuracy_deg"].get<double>(), 2 * 0.023 / 160 * 180 / M_PI, 1e-12);
  int oc_symmetry_flags = 0, sc_symmetry_flags = 0;
  for (const auto& s : j["symmetry"]) (s["mechanism"] == "OC" ? oc_symmetry_flags : sc_symmetry_flags) += s["flagged"].get<bool>();
  EXPECT_LE(oc_symmetry_flags, 2);   // §2.5: OC is symmetric within the accuracy
  EXPECT_GT(sc_symmetry_flags, 100); // §3.3: SC is not
  for (const auto& c : j["oc_vs_sc"]) EXPECT_FALSE(c["flagged"].get<bool>()) << c.dump();
  const CliResult n = run_cli("data check thesis --json --nominal-forces");
  ASSERT_EQ(n.exit_code, 0);
  // SC +x x1y1 dx (a complete series), found by its key in both documents
  const auto find = [](const nlohmann::json& doc) {
    for (const auto& l : doc["linearity"]) {
      if (l["mechanism"] == "SC" && l["direction"] == "+x" && l["point"] == "x1y1" && l["quantity"] == "dx") return l;
    }
    return nlohmann::json();
  };
  const auto nj = n.json();
  const auto a = find(j), b = find(nj);
  ASSERT_EQ(a["point"], "x1y1");
  ASSERT_EQ(b["point"], "x1y1");
  // Every linearity result is a fit through three or more cells: a one-cell "fit" is not a check.
  for (const auto& l : j["linearity"]) EXPECT_GE(l["n"].get<int>(), 3) << l.dump();
  EXPECT_NEAR(b["slope_mm_per_N"].get<double>() / a["slope_mm_per_N"].get<double>(), 0.9734, 0.002);
}

TEST(CliDataCheck, BadTableExits2) {
  TempDir dir;
  write_text(dir / "t.csv", std::string(measurement::kDisplacementColumns) + "\nOC,+x,P,1,2,1,5,48,50,nan,,,,\n");
  const CliResult r = run_cli("data check t.csv", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("t.csv:2:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("column 'dx_mm': 'nan'"), std::string::npos) << r.err;
}

TEST(CliRepeatability, Table32AndABidirectionalFile) {
  const CliResult r = run_cli("repeatability thesis --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = r.json();
  ASSERT_EQ(j["points"].size(), 9U);
  EXPECT_NEAR(j["points"][0]["ap_um"].get<double>(), 851.0616, 1e-3);  // hypot(792.333, 310.667)
  EXPECT_NEAR(j["points"][0]["rp_um"].get<double>(), 3.5422, 1e-3);
  EXPECT_NEAR(j["points"][5]["max_diff_y_um"].get<double>(), 8.0, 1e-9);  // x2y5, table 3.2
  EXPECT_EQ(j["missing"].size(), 9U);

  TempDir dir;
  write_text(dir / "b.csv",
             "point,x_mm,y_mm,trial,approach,err_x_mm,err_y_mm\n"
             "P1,200,0,1,+,0.010,0\nP1,200,0,2,+,0.012,0\nP1,200,0,1,-,0.002,0\nP1,200,0,2,-,0.004,0\n"
             "P2,250,0,1,+,-0.001,0\nP2,250,0,2,+,0.001,0\nP2,250,0,1,-,-0.005,0\nP2,250,0,2,-,-0.003,0\n");
  const CliResult b = run_cli("repeatability b.csv --json", dir.path());
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto bj = b.json();
  const auto& x = bj["vdi3441"][0];
  EXPECT_EQ(x["axis"], "x");
  EXPECT_NEAR(x["position_deviation_um"].get<double>(), 9.0, 1e-9);
  EXPECT_NEAR(x["uncertainty_um"].get<double>(), 23.4852814, 1e-6);  // worked out in test_repeatability.cpp
  const CliResult t = run_cli("repeatability b.csv", dir.path());
  EXPECT_NE(t.out.find("VDI/DGQ 3441 axis x: Pa 9.0 um, U max 8.0 / mean 6.0 um"), std::string::npos) << t.out;
}

}  // namespace
}  // namespace stiffpath::test
