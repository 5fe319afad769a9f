// "Without compensation" is one thing: `run --no-compensation` + `simulate` and `experiment`'s uncompensated run mark
// the same square identically (the plan itself, unfiltered, on the same twin).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "cli_runner.hpp"
#include "stiffpath/core/csv.hpp"

namespace stiffpath::test {
namespace {

// A square in each robot's measured region: the thesis's OC and the example asymmetric robot of its own data.
struct Case {
  const char* robot;
  const char* square;
};
const Case kCases[] = {
    {"oc-gu", "G21 G90 G61\nG0 X202 Y-20\nM3 S1000\nG1 X242 Y-20 F60000\nG1 X242 Y20\nG1 X202 Y20\nG1 X202 Y-20\nM5\nM2\n"},
    {STIFFPATH_SOURCE_DIR "/examples/robots/asym_5bar.json",
     "G21 G90 G61\nG0 X-20 Y190\nM3 S1000\nG1 X20 Y190 F60000\nG1 X20 Y230\nG1 X-20 Y230\nG1 X-20 Y190\nM5\nM2\n"},
};

TEST(WithoutCompensation, RunAndSimulateMarkWhatExperimentMarks) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.robot);
    TempDir dir;
    write_text(dir / "sq.gcode", c.square);
    const std::string robot = std::string("'") + c.robot + "'";
    const CliResult e = run_cli("experiment --robots " + robot + " --path sq.gcode:4 --accelerations-g 5 --variants default "
                                "--no-plots -o exp",
                                dir.path());
    ASSERT_EQ(e.exit_code, 0) << e.err;
    // A binary joint file keeps full doubles, as the experiment's commands are in memory.
    const std::string run = "run sq.gcode --robot " + robot + " --accel 5g --no-compensation --format bin -o plain.bin";
    ASSERT_EQ(run_cli(run, dir.path()).exit_code, 0);
    const CliResult s = run_cli("simulate plain.bin --robot " + robot + " --sides 4 --json", dir.path());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    core::CsvReader results((dir / "exp" / "results.csv").string());
    const auto compensated = results.column("compensated"), duration = results.column("duration_s"),
               deviation = results.column("max_deviation_mm"), area = results.column("deviation_area_mm2"),
               length = results.column("length_mm");
    int rows = 0;
    while (results.next()) {
      if (results.number(compensated) != 0.0) continue;
      ++rows;
      // The experiment's table keeps six decimals.
      EXPECT_NEAR(results.number(duration), s.json()["duration_s"].get<double>(), 1e-6);
      EXPECT_NEAR(results.number(deviation), s.json()["max_deviation_mm"].get<double>(), 1e-6);
      EXPECT_NEAR(results.number(area), s.json()["deviation_area_mm2"].get<double>(), 1e-6);
      EXPECT_NEAR(results.number(length), s.json()["length_mm"].get<double>(), 1e-6);
    }
    EXPECT_EQ(rows, 1);
    // And the plan is the job: no filter lengthens it (the plan's own duration).
    const CliResult plan = run_cli("plan sq.gcode --robot " + robot + " --accel 5g --json", dir.path());
    ASSERT_EQ(plan.exit_code, 0) << plan.err;
    EXPECT_NEAR(plan.json()["duration_s"].get<double>(), s.json()["duration_s"].get<double>(), 1e-9);
  }
}

}  // namespace
}  // namespace stiffpath::test
