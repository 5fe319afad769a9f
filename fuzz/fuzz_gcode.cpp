// libFuzzer harness: the G-code reader and the planner behind it (measure_plan: plans, never samples).
#include <sstream>

#include "fuzz_input.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(stiffpath::fuzz::text(data, size));
  STIFFPATH_FUZZ_EXPECT_REFUSAL({
    const auto plan = stiffpath::motion::measure_plan(in, "fuzz.gcode");
    if (!(plan.duration_s >= 0.0)) __builtin_trap();  // a planned job has a finite, non-negative duration
  })
  return 0;
}
