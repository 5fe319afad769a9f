// libFuzzer harness: the G-code reader and the planner behind it (measure_plan: plans, never samples),
// with the chords blended or, when the input's first byte is odd, fitted (--chords fit).
#include <sstream>

#include "fuzz_input.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(stiffpath::fuzz::text(data, size));
  stiffpath::motion::PlanOptions options;
  options.planner.junction.fit_chords = size > 0 && (data[0] & 1u) != 0;
  STIFFPATH_FUZZ_EXPECT_REFUSAL({
    const auto plan = stiffpath::motion::measure_plan(in, "fuzz.gcode", options);
    if (!(plan.duration_s >= 0.0)) __builtin_trap();  // a planned job has a finite, non-negative duration
  })
  return 0;
}
