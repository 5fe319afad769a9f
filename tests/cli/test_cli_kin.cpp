// End-to-end tests of `stiffpath kin`, `mechanism` and `mobility`: numbers in the output, errors and exit codes.
#include <gtest/gtest.h>

#include <cmath>

#include "cli_runner.hpp"

namespace stiffpath::test {
namespace {

TEST(CliKin, InverseThenForwardRoundTripsThroughJson) {
  const CliResult ik = run_cli("kin ik --x-mm 222.132 --y-mm 37.5 --json");
  ASSERT_EQ(ik.exit_code, 0) << ik.err;
  const auto pose = ik.json();
  const double t1 = pose["theta1_rad"], t2 = pose["theta2_rad"];
  // Independent check of eq. 2.2.
  const double r = std::hypot(222.132, 37.5), phi = std::atan2(37.5, 222.132), eta = std::acos(r / 300.0);
  EXPECT_NEAR(t1, phi + eta, 1e-10);
  EXPECT_NEAR(t2, phi - eta, 1e-10);
  EXPECT_DOUBLE_EQ(pose["theta3_rad"].get<double>(), t2);
  EXPECT_DOUBLE_EQ(pose["theta4_rad"].get<double>(), t1);
  EXPECT_NEAR(pose["condition_number"].get<double>(), 1.0 / std::tan(eta), 1e-9);

  const double deg = 180.0 / M_PI;
  const CliResult fk =
      run_cli("kin fk --theta1-deg " + std::to_string(t1 * deg) + " --theta2-deg " + std::to_string(t2 * deg) + " --json");
  ASSERT_EQ(fk.exit_code, 0) << fk.err;
  EXPECT_NEAR(fk.json()["x_mm"].get<double>(), 222.132, 1e-3);  // std::to_string keeps 6 decimals of degrees
  EXPECT_NEAR(fk.json()["y_mm"].get<double>(), 37.5, 1e-3);
}

TEST(CliKin, SingularPointIsRefusedWithExitCode2) {
  const CliResult r = run_cli("kin ik --x-mm 300 --y-mm 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error: point (x = 300.0000 mm, y = 0.0000 mm) refused"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST(CliKin, GridListsFifteenPointsWithTinyRoundTripError) {
  const CliResult r = run_cli("kin grid --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto points = r.json()["points"];
  ASSERT_EQ(points.size(), 15u);
  EXPECT_EQ(points[0]["point"], "x1y1");
  EXPECT_EQ(points[14]["point"], "x3y5");
  for (const auto& p : points) EXPECT_LT(p["fk_roundtrip_error_nm"].get<double>(), 1e-3);
}

TEST(CliMechanism, ShowPresetAndUserFile) {
  const CliResult r = run_cli("mechanism show sc-gl --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.json()["compliance"]["rows"], "SC");
  EXPECT_DOUBLE_EQ(r.json()["cg"]["height_above_G_mm"].get<double>(), 5.3);

  TempDir dir;
  auto doc = r.json();
  doc["moving_mass_kg"] = -1;
  write_text(dir / "mine.json", doc.dump());
  const CliResult bad = run_cli("mechanism show mine.json", dir.path());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("mine.json:1:"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find(": moving_mass_kg: must be positive, got -1"), std::string::npos) << bad.err;
}

TEST(CliMobility, PrintsEquation32) {
  const CliResult r = run_cli("mobility --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto cases = r.json();
  ASSERT_EQ(cases.size(), 3u);
  EXPECT_EQ(cases[0]["gruebler_kutzbach"], 3);
  EXPECT_EQ(cases[1]["gruebler_kutzbach"], 2);
  EXPECT_EQ(cases[2]["gruebler_kutzbach"], 1);
  EXPECT_EQ(cases[2]["actual_mobility"], 2);
}

TEST(Cli, VersionHelpAndUnknownOption) {
  const CliResult v = run_cli("--version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_NE(v.out.find("stiffpath 0."), std::string::npos);
  const CliResult h = run_cli("kin ik --help");
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_NE(h.out.find("--x-mm"), std::string::npos);
  const CliResult bad = run_cli("kin ik --x-mm abc --y-mm 0");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("abc"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace stiffpath::test
