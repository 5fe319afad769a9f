// libFuzzer harness: plate files (render-scan --plate), loaded and, when they load, rendered at 10 dpi.
#include <cmath>

#include "fuzz_input.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/render/plate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = stiffpath::fuzz::as_file(data, size, ".json");
  STIFFPATH_FUZZ_EXPECT_REFUSAL({
    const stiffpath::vision::Plate plate = stiffpath::vision::load_plate(path);
    stiffpath::vision::RenderOptions options;
    options.dpi = 10;  // every check of the renderer, on a small image
    const auto rendered = stiffpath::vision::render_plate(plate, options);
    // Documented: one truth per mark and per fiducial, every length finite.
    if (rendered.marks.size() != plate.marks.size() || rendered.fiducials_m.size() != plate.fiducials.size()) __builtin_trap();
    for (const auto& m : rendered.marks) {
      if (!std::isfinite(m.truth.length_m)) __builtin_trap();
    }
  })
  return 0;
}
