// libFuzzer harness: the image-metadata readers (PNG pHYs, TIFF XResolution, JPEG JFIF/Exif), in memory.
#include <cmath>
#include <span>

#include "stiffpath/vision/io/resolution.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  const auto r = stiffpath::vision::resolution_from_memory(bytes);
  // Documented: a found resolution is positive and finite.
  if (r && !(std::isfinite(r->dpi_x) && r->dpi_x > 0 && std::isfinite(r->dpi_y) && r->dpi_y > 0)) __builtin_trap();
  // What the file stores is said in words whenever something is stored, and a stored density is finite and >= 0.
  const auto stored = stiffpath::vision::stored_resolution_from_memory(bytes);
  using Kind = stiffpath::vision::StoredResolution::Kind;
  if (stored.kind != Kind::none && (stored.stored.empty() || stored.source.empty())) __builtin_trap();
  if (stored.kind == Kind::value && !(std::isfinite(stored.dpi_x) && stored.dpi_x >= 0 && std::isfinite(stored.dpi_y) && stored.dpi_y >= 0)) {
    __builtin_trap();
  }
  return 0;
}
