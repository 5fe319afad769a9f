// `stiffpath calibrate plate`: the plate's files and its count of each kind of mark, and a plate the planner runs.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using namespace stiffpath::test;

// For oc-gu's 2 × 2 stations, three directions and two accelerations: a ringing stroke per station, direction and
// level (24), a timing stroke per station and direction (12), an arc per station and level (8); plate.json lists
// the same, by kind; and the program plans inside the robot's workspace.
TEST(CliCalibratePlate, CountsEachKindOfMarkAndThePlanRuns) {
  TempDir dir;
  const CliResult r = run_cli("calibrate plate --robot oc-gu -o plate --json", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = r.json();
  EXPECT_EQ(j["ringing_strokes"].get<int>(), 24);
  EXPECT_EQ(j["timing_strokes"].get<int>(), 12);
  EXPECT_EQ(j["arcs"].get<int>(), 8);
  EXPECT_EQ(j["marks"].get<int>(), 44);
  std::ifstream in(dir.path() / "plate" / "plate.json");
  const auto plate = nlohmann::json::parse(in);
  int ringing = 0, timing = 0, arcs = 0;
  for (const auto& m : plate["marks"]) {
    const std::string kind = m["kind"];
    ringing += kind == "ringing", timing += kind == "timing", arcs += kind == "arc";
    if (kind == "arc") EXPECT_DOUBLE_EQ(m["sweep_deg"].get<double>(), 270.0);
    if (kind == "timing") EXPECT_GT(m["run_mm"].get<double>(), 0.0);
  }
  EXPECT_EQ(ringing, 24);
  EXPECT_EQ(timing, 12);
  EXPECT_EQ(arcs, 8);
  const CliResult plan = run_cli("plan plate/plate.gcode --robot oc-gu --json", dir.path());
  EXPECT_EQ(plan.exit_code, 0) << plan.err;
}
