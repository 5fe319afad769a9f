// Every refusal about robots and their data: the message names what is wrong, exit code 2, no output left behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <cmath>
#include <fstream>
#include <sstream>

#include "cli_runner.hpp"
#include "own_robot.hpp"

namespace stiffpath::test {
namespace {

const OwnRobot kRobot;

struct Workspace {
  TempDir dir;
  Workspace() {
    write_text(dir / "robot.json", kRobot.file("table.csv"));
    write_text(dir / "table.csv", table_of([](const V2& c) { return known_compliance(kRobot, c); }));
  }
  CliResult run(const std::string& args) const { return run_cli(args, dir.path()); }
  // Nothing but the inputs (and what the test wrote) in the folder: no output, no temporary file.
  void expect_only(std::initializer_list<std::string> names) const {
    for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
      const std::string name = e.path().filename().string();
      EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << "left behind: " << name;
    }
  }
};

TEST(CliRobotRefusals, AModelFittedForAnotherGeometryIsRefusedUnlessForced) {
  const Workspace w;
  write_text(w.dir / "job.gcode", "G21 G90\nG0 X10 Y175\nM3 S100\nG1 Y245 F60000\nM5\n");
  const CliResult r = w.run("run job.gcode --robot robot.json --model thesis-oc -o out.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("error: model thesis-oc was fitted for robot 'oc-gu' (geometry ", 0), 0U) << r.err;
  EXPECT_NE(r.err.find("), not for robot 'asym' (geometry "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("pass --force-model"), std::string::npos) << r.err;
  // A model file fitted for this robot is refused for the thesis robot, naming both.
  ASSERT_EQ(w.run("fit --robot robot.json --method physical -o mine.json").exit_code, 0);
  const CliResult back = w.run("predict --robot oc-gu --model mine.json --x-mm 220 --y-mm 0 --fx-n 1 --fy-n 0");
  EXPECT_EQ(back.exit_code, 2);
  EXPECT_NE(back.err.find("model mine.json was fitted for robot 'asym'"), std::string::npos) << back.err;
  EXPECT_NE(back.err.find("not for robot 'oc-gu'"), std::string::npos) << back.err;
  // Forced, the thesis model is used, and then the job is refused for leaving its measured region.
  const CliResult forced = w.run("run job.gcode --robot robot.json --model thesis-oc --force-model -o out.csv");
  EXPECT_EQ(forced.exit_code, 2);
  EXPECT_NE(forced.err.find("job.gcode:4: t = 0.0000 s: (x = 10.0000 mm, y = 175.0000 mm) is more than 1 mm outside the "
                            "compliance model's measured region x [172.132, 272.132] mm"),
            std::string::npos)
      << forced.err;
  w.expect_only({"robot.json", "table.csv", "job.gcode", "mine.json"});
}

TEST(CliRobotRefusals, AJobLeavingTheMeasuredRegionIsRefusedAtItsFirstSample) {
  const Workspace w;
  // The rectangle ends at y = 250 mm; the move goes on to 262 mm.
  write_text(w.dir / "job.gcode", "G21 G90\nG0 X0 Y200\nM3 S100\nG1 Y262 F60000\nM5\n");
  const CliResult r = w.run("run job.gcode --robot robot.json -o out.bin --format bin");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error: job.gcode:4: t = "), std::string::npos) << r.err;
  // The first sample beyond 251 mm (the 1 mm margin).
  const auto at = r.err.find("y = 251.");
  EXPECT_NE(at, std::string::npos) << r.err;
  EXPECT_NE(r.err.find("is more than 1 mm outside the compliance model's measured region x [-60.000, 60.000] mm, y "
                       "[170.000, 250.000] mm (use --outside clamp or extrapolate to go on anyway)"),
            std::string::npos)
      << r.err;
  w.expect_only({"robot.json", "table.csv", "job.gcode"});
  // Explicitly clamped, the same job runs and counts the samples outside.
  const CliResult clamped = w.run("run job.gcode --robot robot.json --outside clamp -o out.bin --format bin --json");
  ASSERT_EQ(clamped.exit_code, 0) << clamped.err;
  EXPECT_GT(clamped.json()["samples_outside_grid"].get<int>(), 10);
}

TEST(CliRobotRefusals, KinAndPlanHonourTheJointLimitsAndTheWorkspace) {
  const Workspace w;
  // (150, 60) mm closes the loop, but the right arm would stand at −54.9°, below its −45° limit.
  const V2 q = kRobot.joints({0.150, 0.060});
  ASSERT_NEAR(q.y() * 180 / M_PI, -54.868, 0.01);
  const CliResult ik = w.run("kin ik --robot robot.json --x-mm 150 --y-mm 60");
  EXPECT_EQ(ik.exit_code, 2);
  EXPECT_EQ(ik.err, fmt::format("error: point (x = 150.0000 mm, y = 60.0000 mm) refused: joint theta2 would be at {:.3f} "
                                "deg, outside its range [-45.0, 135.0] deg\n",
                                q.y() * 180 / M_PI));
  const CliResult fk = w.run("kin fk --robot robot.json --theta1-deg 30 --theta2-deg 20");
  EXPECT_EQ(fk.exit_code, 2);
  EXPECT_EQ(fk.err, "error: joint theta1 = 0.523599 rad (30 deg) is outside its range [45.0, 225.0] deg on robot 'asym'\n");
  const CliResult stretched = w.run("kin ik --robot robot.json --x-mm 0 --y-mm 330");
  EXPECT_EQ(stretched.exit_code, 2);
  EXPECT_NE(stretched.err.find("too close to the stretched-out singularity: the left arm would reach"), std::string::npos)
      << stretched.err;

  // Angles that put the left elbow on the other side of A1C reach (0, 210) mm in another working mode:
  // fk says so instead of calling the pose reachable (joint ranges widened so that it is not refused).
  std::string wide = kRobot.file("table.csv");
  for (const char* limit : {"\"min_deg\": 45, \"max_deg\": 225", "\"min_deg\": -45, \"max_deg\": 135"}) {
    wide.replace(wide.find(limit), std::string(limit).size(), "\"min_deg\": -180, \"max_deg\": 180");
  }
  write_text(w.dir / "wide.json", wide);
  const V2 home = kRobot.joints({0.0, 0.210});
  const double flipped = 2 * std::atan2(0.210, 0.040) - home.x();
  const CliResult other = w.run(fmt::format("kin fk --robot wide.json --theta1-deg {:.9f} --theta2-deg {:.9f} --json",
                                            flipped * 180 / M_PI, home.y() * 180 / M_PI));
  ASSERT_EQ(other.exit_code, 0) << other.err;
  EXPECT_NEAR(other.json()["x_mm"].get<double>(), 0.0, 1e-5);
  EXPECT_NEAR(other.json()["y_mm"].get<double>(), 210.0, 1e-5);
  EXPECT_EQ(other.json()["reach"], "these angles put the elbows out of the robot's working mode (elbows [+1, -1])");
  std::filesystem::remove(w.dir / "wide.json");

  write_text(w.dir / "far.gcode", "G21 G90\nG0 X0 Y200\nG1 Y320 F60000\n");
  const CliResult plan = w.run("plan far.gcode --robot robot.json -o traj.csv");
  EXPECT_EQ(plan.exit_code, 2);
  EXPECT_NE(plan.err.find("error: far.gcode:3: t = "), std::string::npos) << plan.err;
  EXPECT_NE(plan.err.find("is outside robot asym's workspace: too close to the stretched-out singularity"),
            std::string::npos)
      << plan.err;
  w.expect_only({"robot.json", "table.csv", "far.gcode"});
  // The same program inside the workspace plans.
  write_text(w.dir / "near.gcode", "G21 G90\nG0 X0 Y200\nG1 Y240 F60000\n");
  EXPECT_EQ(w.run("plan near.gcode --robot robot.json").exit_code, 0);
}

TEST(CliRobotRefusals, BadRobotFilesNameLineColumnAndField) {
  const Workspace w;
  std::string text = kRobot.file("table.csv");
  text.replace(text.find("\"table\""), 7, "\"dataset\"");
  write_text(w.dir / "old.json", text);
  const CliResult r = w.run("fit --robot old.json -o m.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "error: old.json:10:18: compliance.dataset: unknown field (use table)\n");
  write_text(w.dir / "typo.json", kRobot.file("tabel.csv"));
  const CliResult t = w.run("run x.gcode --robot typo.json -o m.csv");
  EXPECT_EQ(t.exit_code, 2);
  EXPECT_EQ(t.err, "error: typo.json:10:18: compliance.table: no such file: tabel.csv\n");
  w.expect_only({"robot.json", "table.csv", "old.json", "typo.json"});
}

TEST(CliRobotRefusals, GridMethodsNeedAFullGridAndCvSaysWhichCouldNotRun) {
  const Workspace w;
  // Drop point p23 ((−20, 250) mm): eleven points, no longer a full 4 × 3 grid.
  std::string table = table_of([](const V2& c) { return known_compliance(kRobot, c); }), kept;
  std::istringstream in(table);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("p23,", 0) != 0) kept += line + "\n";
  }
  write_text(w.dir / "table.csv", kept);
  const CliResult cv = w.run("cv --robot robot.json --json");
  ASSERT_EQ(cv.exit_code, 0) << cv.err;
  const auto report = cv.json();
  ASSERT_EQ(report["could_not_run"].size(), 2U);
  EXPECT_EQ(report["could_not_run"][0]["method"], "bilinear");
  EXPECT_EQ(report["could_not_run"][0]["reason"],
            "needs a full rectangular grid: the points do not form a full grid: nothing measured at (-20.000, 250.000) mm");
  EXPECT_EQ(report["methods"].size(), 4U);
  EXPECT_EQ(report["favoured_method"], "physical");
  const CliResult text = w.run("cv --robot robot.json");
  EXPECT_NE(text.out.find("bilinear         could not run: needs a full rectangular grid"), std::string::npos) << text.out;
  const CliResult fit = w.run("fit --robot robot.json --method bilinear -o m.json");
  EXPECT_EQ(fit.exit_code, 2);
  EXPECT_NE(fit.err.find("nothing measured at (-20.000, 250.000) mm"), std::string::npos) << fit.err;
  EXPECT_EQ(w.run("fit --robot robot.json -o auto.json").exit_code, 0);  // the physical model runs on any layout
  w.expect_only({"robot.json", "table.csv", "auto.json"});
}

TEST(CliRobotRefusals, TwinAndMeasurementCommandsNeedWhatTheRobotLacks) {
  const Workspace w;
  write_text(w.dir / "job.gcode", "G21 G90\nG0 X10 Y175\nM3 S100\nG1 Y245 F60000\nM5\n");
  ASSERT_EQ(w.run("run job.gcode --robot robot.json --format bin -o j.bin").exit_code, 0);
  // A binary joint file names its robot; one that is not a preset must be named again.
  const CliResult sim = w.run("simulate j.bin");
  EXPECT_EQ(sim.exit_code, 2);
  EXPECT_EQ(sim.err, "error: j.bin: the joint file was written for robot 'asym', which is not a preset: name its robot "
                     "file with --robot\n");
  const CliResult wrong = w.run("simulate j.bin --robot oc-gu");
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_NE(wrong.err.find("error: j.bin: the joint file was written for robot 'asym' (geometry "), std::string::npos)
      << wrong.err;
  EXPECT_NE(wrong.err.find("not for 'oc-gu' (geometry "), std::string::npos) << wrong.err;
  EXPECT_NE(wrong.err.find("--force-robot"), std::string::npos) << wrong.err;
  // No CMM replica in this robot file: eq. 2.3 cannot be applied.
  const CliResult camp = w.run("campaign simulate --robot robot.json -o c.csv");
  EXPECT_EQ(camp.exit_code, 2);
  EXPECT_NE(camp.err.find("robot 'asym' has no measurement replica (measurement.UG_mm, UL_mm)"), std::string::npos)
      << camp.err;
  const CliResult meas = w.run("measure c.csv --robot robot.json -o t.csv");
  EXPECT_EQ(meas.exit_code, 2);
  EXPECT_NE(meas.err.find("robot 'asym' has no measurement replica"), std::string::npos) << meas.err;
  // A robot without any compliance data cannot run compensated jobs or a twin.
  std::string bare = kRobot.file("table.csv");
  bare.replace(bare.find(",\n  \"compliance\""), bare.find("}\n}") + 1 - bare.find(",\n  \"compliance\""), "");
  write_text(w.dir / "bare.json", bare);
  const CliResult none = w.run("run job.gcode --robot bare.json -o x.csv");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("robot 'asym' has no compliance data: give compliance.table or compliance.model"),
            std::string::npos)
      << none.err;
  const CliResult exp = w.run("experiment --robot bare.json -o out --no-plots");
  EXPECT_EQ(exp.exit_code, 2);
  EXPECT_NE(exp.err.find("has no compliance data for the digital twin"), std::string::npos) << exp.err;
  w.expect_only({"robot.json", "table.csv", "job.gcode", "j.bin", "bare.json"});
  // Without compensation it needs none: reach and joint limits only, commands on the plan.
  const CliResult plain = w.run("run job.gcode --robot bare.json --no-compensation -o plain.csv --json");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(plain.json()["model"], "none");
  EXPECT_EQ(plain.json()["peak_correction_um"], 0.0);
}

TEST(CliRobotRefusals, AJointFileWithoutItsRobotSaysWhichRobotIsAssumed) {
  const Workspace w;
  write_text(w.dir / "job.gcode", "G21 G90\nG0 X247 Y-50\nM3 S100\nG1 Y50 F60000\nM5\n");
  ASSERT_EQ(w.run("run job.gcode -o j.csv").exit_code, 0);
  // The same rows without the first line, where the file records its robot: as a user's own CSV would be.
  std::ifstream in(w.dir / "j.csv");
  std::string first;
  std::getline(in, first);
  ASSERT_EQ(first.rfind("# stiffpath joints", 0), 0U) << first;
  std::stringstream rest;
  rest << in.rdbuf();
  write_text(w.dir / "bare.csv", rest.str());
  const CliResult assumed = w.run("simulate bare.csv --json");
  ASSERT_EQ(assumed.exit_code, 0) << assumed.err;
  EXPECT_EQ(assumed.err, "warning: bare.csv: the joint file does not record its robot; using the default robot "
                         "'oc-gu' (name another with --robot)\n");
  // Named, or recorded in the file, there is nothing to warn about.
  EXPECT_EQ(w.run("simulate bare.csv --robot oc-gu --json").err, "");
  EXPECT_EQ(w.run("simulate j.csv --json").err, "");
}

TEST(CliRobotRefusals, AModelFileOfFormatOneNeedsForcing) {
  const Workspace w;
  ASSERT_EQ(w.run("fit --robot robot.json --method bilinear -o m.json").exit_code, 0);
  // The same model as version 1 wrote it: no robot block, so no geometry to check.
  std::ifstream in(w.dir / "m.json");
  auto doc = nlohmann::json::parse(in);
  doc["version"] = 1;
  doc.erase("robot");
  write_text(w.dir / "old.json", doc.dump(2));
  write_text(w.dir / "job.gcode", "G21 G90\nG0 X10 Y175\nM3 S100\nG1 Y245 F60000\nM5\n");
  const CliResult r = w.run("run job.gcode --robot robot.json --model old.json -o out.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "error: model old.json does not record the robot geometry it was fitted for (a file of format "
                   "version 1): refit it for robot 'asym' or pass --force-model\n");
  w.expect_only({"robot.json", "table.csv", "m.json", "old.json", "job.gcode"});
  // Forced, it is used as it stands.
  const CliResult forced = w.run("run job.gcode --robot robot.json --model old.json --force-model -o out.csv");
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_TRUE(std::filesystem::exists(w.dir / "out.csv"));
}

}  // namespace
}  // namespace stiffpath::test
