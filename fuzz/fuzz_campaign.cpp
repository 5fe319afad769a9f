// libFuzzer harness: the CMM campaign loader.
#include "fuzz_input.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/campaign.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = stiffpath::fuzz::as_file(data, size, ".csv");
  STIFFPATH_FUZZ_EXPECT_REFUSAL({ (void)stiffpath::measurement::load_campaign(path); })
  return 0;
}
