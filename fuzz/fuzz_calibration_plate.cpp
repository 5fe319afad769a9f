// libFuzzer harness: calibration plates (calibrate fit's plate.json), loaded and, when they load, written and read back.
#include <cmath>
#include <cstdio>

#include "fuzz_input.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = stiffpath::fuzz::as_file(data, size, ".json");
  STIFFPATH_FUZZ_EXPECT_REFUSAL({
    const stiffpath::calibration::PlateDesign plate = stiffpath::calibration::load_plate(path);
    // Documented: every mark's path finite (an arc's sampled at most every 2°), and the plate as plate_json writes
    // it reads back with the same marks.
    for (const auto& m : plate.strokes) {
      for (const auto& p : m.polyline_m()) {
        if (!p.allFinite()) __builtin_trap();
      }
      if (!m.start_direction().allFinite() || !m.end_direction().allFinite()) __builtin_trap();
    }
    (void)stiffpath::calibration::plate_gcode(plate);
    const std::string again = path + ".again.json";
    if (std::FILE* f = std::fopen(again.c_str(), "w")) {
      const std::string text = stiffpath::calibration::plate_json(plate);
      std::fwrite(text.data(), 1, text.size(), f);
      std::fclose(f);
      const auto back = stiffpath::calibration::load_plate(again);
      if (back.strokes.size() != plate.strokes.size() || back.fiducials.size() != plate.fiducials.size()) __builtin_trap();
    }
  })
  return 0;
}
