// The look-ahead's work per segment is bounded: entry evaluations counted by the planner, not timed.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "chord_programs.hpp"
#include "planner_checks.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::motion {
namespace {

PlannerStatistics plan_statistics(const std::string& gcode, const PlannerOptions& options = {}) {
  std::istringstream in(gcode);
  GcodeReader reader(in, "job.gcode");
  CornerBlender blender(reader, options.junction.corner_angle_rad);
  Planner planner(blender, MotionLimits{}, options);
  while (planner.next()) {
  }
  return planner.statistics();
}

// With a backward pass after every segment, each new segment re-raises the entries of all the
// segments it takes to brake from the speed reached: about 13 on the gear outline, 26 on 0.1 mm
// chords at 340 mm/s and thousands on 5 µm pieces of a line. Batched, the total stays below
// 4·runs + 2·(largest window + 1) (planner.cpp). The window is the whole line in the third program
// planned one profile per segment, which never reaches a pinned speed; elsewhere it is short and
// the cost at most 3 per segment. Both with runs and with one profile per segment.
TEST(LookAheadWork, EntryEvaluationsStayWithinTheirBound) {
  struct Program {
    const char* what;
    std::string gcode;
  };
  std::ostringstream gear;
  gear << std::ifstream(STIFFPATH_SOURCE_DIR "/examples/gear_outline.gcode").rdbuf();
  const Program programs[] = {
      {"gear outline", gear.str()},
      {"circle of 0.1 mm chords at 340 mm/s, 20 turns", test::chord_circle(222.132, 0.0, 10.0, 0.1, 20400, 4, "G64 P0.01", 20)},
      {"100 mm line in 20 000 pieces at 2 m/s", test::split_line(172.132, 272.132, 0.0, 20000, 120000)},
      {"exact stops on 0.1 mm chords", test::chord_circle(222.132, 0.0, 10.0, 0.1, 20400, 4, "G61")},
  };
  for (const Program& p : programs) {
    for (const bool runs : {true, false}) {
      PlannerOptions options;
      options.one_profile_per_run = runs;
      const PlannerStatistics s = plan_statistics(p.gcode, options);
      SCOPED_TRACE(std::string(p.what) + (runs ? ", runs" : ", one profile per segment"));
      ASSERT_GT(s.segments, 600u);
      EXPECT_LE(s.entry_evaluations, 4 * s.runs + 2 * (s.peak_window + 1))
          << s.entry_evaluations << " for " << s.runs << " runs, window " << s.peak_window;
      if (s.peak_window < s.segments / 10) {
        EXPECT_LE(s.entry_evaluations, 3 * s.segments) << s.entry_evaluations << " for " << s.segments;
      }
    }
  }
}

TEST(LookAheadWork, AWindowOfTwoStaysFeasibleAndIsNeverFaster) {
  // A bounded window of two runs the pending pass before every release; its plan must still be
  // feasible and, one profile per segment, no faster than the whole-program plan.
  const std::string gcode = test::chord_circle(222.132, 0.0, 5.0, 0.1, 12000);
  PlanOptions whole, bounded;
  whole.planner.one_profile_per_run = bounded.planner.one_profile_per_run = false;
  bounded.planner.max_lookahead_segments = 2;
  const Trajectory exact = test::plan_text(gcode, whole), windowed = test::plan_text(gcode, bounded);
  test::expect_within_limits(windowed, bounded.limits, 4);
  test::expect_continuous_junctions(windowed, bounded.limits);
  EXPECT_GE(windowed.duration_s(), exact.duration_s() * (1 - 1e-12));
}

}  // namespace
}  // namespace stiffpath::motion
