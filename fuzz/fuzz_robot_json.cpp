// libFuzzer harness: the robot-file JSON loader (geometry, limits, references to data files).
#include "fuzz_input.hpp"
#include "stiffpath/core/data_ref.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/robot.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = stiffpath::fuzz::text(data, size);
  STIFFPATH_FUZZ_EXPECT_REFUSAL({ (void)stiffpath::kinematics::parse_robot(text, stiffpath::core::DataRef{"fuzz.json"}); })
  return 0;
}
