// libFuzzer harness: the joint-file reader, CSV and binary (recognised by its magic), read to the end.
#include <cmath>

#include "fuzz_input.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/joint_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = stiffpath::fuzz::as_file(data, size, ".joints");
  STIFFPATH_FUZZ_EXPECT_REFUSAL({
    stiffpath::job::JointReader reader(path);
    double last = -INFINITY;
    while (const auto r = reader.next()) {
      // What the reader hands on is finite and increasing in time (the twin relies on both).
      if (!std::isfinite(r->t_s) || !(r->t_s > last) || !r->q_rad.allFinite()) __builtin_trap();
      last = r->t_s;
    }
  })
  return 0;
}
