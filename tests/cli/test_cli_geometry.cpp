// `geometry plan → simulate → fit` end to end: the calibrated robot file, read by `kin fk`, predicts what the instrument reads.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.hpp"

namespace stiffpath::test {
namespace {

const std::string kRobots = STIFFPATH_SOURCE_DIR "/examples/robots/";

TEST(CliGeometry, ACalibratedRobotFilePredictsTheInstrumentsReadingsAtHeldOutPoses) {
  TempDir dir;
  const auto run = [&](const std::string& args) { return run_cli(args, dir.path()); };
  const CliResult plan = run("geometry plan --robot " + kRobots + "asym_5bar.json --readings 24 -o poses.csv --json");
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  EXPECT_EQ(plan.json()["poses"].get<int>(), 24);
  const CliResult sim = run("geometry simulate --truth " + kRobots + "asym_5bar_as_built.json --poses poses.csv -o readings.csv "
                            "--instrument-rotation-deg 140 --instrument-shift-mm 812 -230 0 --seed 5");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const CliResult fit = run("geometry fit readings.csv --robot " + kRobots + "asym_5bar.json -o asym_geo.json --no-plots --json");
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const auto report = fit.json();
  EXPECT_GT(report["rms_before_um"].get<double>(), 50.0);
  EXPECT_LT(report["rms_after_um"].get<double>(), 15.0);
  EXPECT_TRUE(std::filesystem::exists(dir / "asym_geo_report" / "geometry_fit.json"));
  // Held-out poses, read exactly by the same instrument.
  write_text(dir / "held_out.csv", "theta1_deg,theta2_deg\n100,60\n140,95\n75,30\n120,40\n");
  ASSERT_EQ(run("geometry simulate --truth " + kRobots + "asym_5bar_as_built.json --poses held_out.csv -o exact.csv "
                "--instrument-rotation-deg 140 --instrument-shift-mm 812 -230 0 --noise-um 0")
                .exit_code,
            0);
  std::ifstream exact(dir / "exact.csv");
  std::string line;
  std::getline(exact, line);
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R(i, j) = report["instrument"]["rotation"][i][j].get<double>();
  }
  const auto& t = report["instrument"]["translation_mm"];
  const Eigen::Vector3d shift(t[0].get<double>(), t[1].get<double>(), t[2].get<double>());
  int checked = 0;
  while (std::getline(exact, line)) {
    double t1 = 0, t2 = 0, x = 0, y = 0;
    int reading = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%d", &t1, &t2, &x, &y, &reading), 5) << line;
    // The calibrated robot's own forward kinematics, through the fitted instrument frame.
    const CliResult fk = run(fmt::format("kin fk --robot asym_geo.json --theta1-deg {:.9f} --theta2-deg {:.9f} --json", t1, t2));
    ASSERT_EQ(fk.exit_code, 0) << fk.err;
    const Eigen::Vector3d p(fk.json()["x_mm"].get<double>(), fk.json()["y_mm"].get<double>(), 0.0);
    const Eigen::Vector3d seen = R * p + shift;
    EXPECT_LT(std::hypot(seen.x() - x, seen.y() - y) * 1e3, 1.5 * 11.5) << line;  // within 1.5× the arm's σ
    // The robot file's own geometry is off by far more.
    const CliResult nominal = run(fmt::format("kin fk --robot {}asym_5bar.json --theta1-deg {:.9f} --theta2-deg {:.9f} --json",
                                                 kRobots, t1, t2));
    const Eigen::Vector3d q(nominal.json()["x_mm"].get<double>(), nominal.json()["y_mm"].get<double>(), 0.0);
    EXPECT_GT((p - q).norm() * 1e3, 50.0);
    ++checked;
  }
  EXPECT_EQ(checked, 4);
  // The calibrated file names its table by an absolute path and is accepted by the commands that read a robot.
  const CliResult show = run("robot show asym_geo.json --json");
  ASSERT_EQ(show.exit_code, 0) << show.err;
  EXPECT_TRUE(std::filesystem::path(show.json()["compliance"]["table"].get<std::string>()).is_absolute());
  EXPECT_TRUE(show.json().contains("joint_zero_offsets_deg"));
  EXPECT_EQ(run("predict --robot asym_geo.json --x-mm 0 --y-mm 210 --fx-n 50 --fy-n 0 --json").exit_code, 0);
}

TEST(CliGeometry, ABadReadingIsRefusedWithItsPlaceAndNothingIsWritten) {
  TempDir dir;
  write_text(dir / "r.csv", "theta1_deg,theta2_deg,x_mm,y_mm\n100,60,1,2\n140,95,inf,4\n");
  const CliResult r = run_cli("geometry fit r.csv --robot " + kRobots + "asym_5bar.json -o out.json", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("r.csv:3:8: column 'x_mm': 'inf' is not a finite number"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.json"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out_report"));
  // Too few readings for the parameters.
  write_text(dir / "few.csv", "theta1_deg,theta2_deg,x_mm,y_mm\n100,60,1,2\n140,95,3,4\n");
  const CliResult few = run_cli("geometry fit few.csv --robot " + kRobots + "asym_5bar.json -o out.json", dir.path());
  EXPECT_EQ(few.exit_code, 2);
  EXPECT_NE(few.err.find("measure more poses"), std::string::npos) << few.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.json"));
}

}  // namespace
}  // namespace stiffpath::test
