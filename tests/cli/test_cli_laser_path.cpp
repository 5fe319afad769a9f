// End to end: the reference filters keep the laser-on path, so `simulate` finds every stroke `run` was given.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"

namespace {

using stiffpath::test::run_cli;
using stiffpath::test::TempDir;
using stiffpath::test::write_text;

// Two 40 mm strokes with a rapid between them (G61): along +x at y = -20 mm, back along -x at y = -19 mm. Smoothed
// over 20 ms in Cartesian space the ends of the strokes were pulled 56 um towards the rapid and the strokes
// shortened; retimed along the path they keep their length at any smoothing and shaper.
TEST(CliLaserPath, SimulateFindsBothStrokesWithTheirCommandedLengths) {
  TempDir dir;
  write_text(dir / "two.gcode",
             "G21 G90 G61\nG0 X190 Y-30\nG0 X200 Y-20\nM3 S1000\nG1 X240 Y-20 F120000\nM5\nG0 X240 Y-19\nM3 S1000\n"
             "G1 X200 Y-19\nM5\nM2\n");
  for (const std::string flags : {"--smooth-ms 8", "--smooth-ms 20", "--smooth-ms 100", "--shaper zvd"}) {
    const auto run = run_cli("run two.gcode --format bin -o j.bin " + flags, dir.path());
    ASSERT_EQ(run.exit_code, 0) << flags << ": " << run.err;
    const auto sim = run_cli("simulate j.bin --sides 1 --json", dir.path());
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    const auto doc = nlohmann::json::parse(sim.out);
    ASSERT_EQ(doc["strokes"].get<int>(), 2) << flags;
    ASSERT_EQ(doc["stroke_metrics"].size(), 2u) << flags;
    for (const auto& stroke : doc["stroke_metrics"]) {
      EXPECT_NEAR(stroke["commanded_length_mm"].get<double>(), 40.0, 1e-3) << flags;
    }
  }
}

}  // namespace
