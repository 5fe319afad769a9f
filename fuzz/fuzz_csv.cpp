// libFuzzer harness: the CSV reader (records, numbers, integers and its located failures).
#include <sstream>

#include "fuzz_input.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(stiffpath::fuzz::text(data, size));
  STIFFPATH_FUZZ_EXPECT_REFUSAL({
    stiffpath::core::CsvReader csv(in, "fuzz.csv");
    while (csv.next()) {
      for (std::size_t c = 0; c < csv.header().size(); ++c) {
        STIFFPATH_FUZZ_EXPECT_REFUSAL({ (void)csv.number(c); })
        STIFFPATH_FUZZ_EXPECT_REFUSAL({ (void)csv.integer(c); })
        (void)csv.optional_number(c);
      }
    }
  })
  return 0;
}
