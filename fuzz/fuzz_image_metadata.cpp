// libFuzzer harness: the image-metadata readers (PNG pHYs, TIFF XResolution, JPEG JFIF/Exif), in memory.
#include <cmath>
#include <span>

#include "stiffpath/vision/io/resolution.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto r = stiffpath::vision::resolution_from_memory(std::span<const std::uint8_t>(data, size));
  // Documented: a found resolution is positive and finite.
  if (r && !(std::isfinite(r->dpi_x) && r->dpi_x > 0 && std::isfinite(r->dpi_y) && r->dpi_y > 0)) __builtin_trap();
  return 0;
}
