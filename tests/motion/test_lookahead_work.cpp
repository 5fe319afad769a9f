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
// 2·(segments + largest window + 1): each pass's work is paid for by the segments that waited for
// the next one, all but the last two. The window is the whole line in the third program, which
// never reaches a pinned speed; in the others it is short and the cost 2 per segment.
TEST(LookAheadWork, EntryEvaluationsStayBelowTwicePerSegmentPlusTheWindow) {
  struct Program {
    const char* what;
    std::string gcode;
  };
  const Program programs[] = {
      {"gear outline", std::string(STIFFPATH_SOURCE_DIR "/examples/gear_outline.gcode")},
      {"circle of 0.1 mm chords at 340 mm/s, 20 turns", test::chord_circle(222.132, 0.0, 10.0, 0.1, 20400, 4, "G64 P0.01", 20)},
      {"100 mm line in 20 000 pieces at 2 m/s", test::split_line(172.132, 272.132, 0.0, 20000, 120000)},
      {"exact stops on 0.1 mm chords", test::chord_circle(222.132, 0.0, 10.0, 0.1, 20400, 4, "G61")},
  };
  for (const Program& p : programs) {
    std::string gcode = p.gcode;
    if (gcode.rfind(STIFFPATH_SOURCE_DIR, 0) == 0) {
      std::ostringstream text;
      text << std::ifstream(gcode).rdbuf();
      gcode = text.str();
    }
    const PlannerStatistics s = plan_statistics(gcode);
    ASSERT_GT(s.segments, 600u) << p.what;
    EXPECT_LE(s.entry_evaluations, 2 * (s.segments + s.peak_window + 1))
        << p.what << ": " << s.entry_evaluations << " for " << s.segments << " segments, window " << s.peak_window;
    if (s.peak_window < s.segments / 10) {
      EXPECT_LE(s.entry_evaluations, 5 * s.segments / 2) << p.what;
    }
  }
}

TEST(LookAheadWork, BatchedPassesGiveTheSamePlanAsAWindowOfOne) {
  // A bounded window of two runs the pending pass before every release; its plan must still be
  // feasible and no faster than the whole-program plan, whose passes are batched.
  const std::string gcode = test::chord_circle(222.132, 0.0, 5.0, 0.1, 12000);
  PlanOptions bounded;
  bounded.planner.max_lookahead_segments = 2;
  const Trajectory whole = test::plan_text(gcode), windowed = test::plan_text(gcode, bounded);
  test::expect_within_limits(windowed, bounded.limits, 4);
  test::expect_continuous_junctions(windowed, bounded.limits);
  EXPECT_GE(windowed.duration_s(), whole.duration_s() * (1 - 1e-12));
}

}  // namespace
}  // namespace stiffpath::motion
