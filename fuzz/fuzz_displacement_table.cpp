// libFuzzer harness: the displacement-table loader (thesis tables 2.2-3.9) and a fit of what it accepts.
#include "fuzz_input.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = stiffpath::fuzz::as_file(data, size, ".csv");
  STIFFPATH_FUZZ_EXPECT_REFUSAL({ (void)stiffpath::measurement::load_displacement_table(path); })
  return 0;
}
