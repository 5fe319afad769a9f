// libFuzzer harness: the repeatability-trials loader (thesis tables 3.2-3.3).
#include "fuzz_input.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/repeatability.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = stiffpath::fuzz::as_file(data, size, ".csv");
  STIFFPATH_FUZZ_EXPECT_REFUSAL({ (void)stiffpath::measurement::load_trials(path); })
  return 0;
}
