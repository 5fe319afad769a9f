// Writing the resolution into PNG (pHYs chunk) and JPEG (JFIF APP0 density) files, and the PNG CRC-32.
#include <array>
#include <cmath>
#include <cstring>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/io/resolution.hpp"

namespace stiffpath::vision {

namespace {

void put_be32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}
std::uint32_t get_be32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

void check_dpi(double dpi) {
  if (!(dpi > 0.0) || !std::isfinite(dpi) || dpi > 65535.0) {
    throw Error(fmt::format("resolution must be a positive number of dpi up to 65535, got {}", dpi));
  }
}

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> bytes) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1U) ? 0xEDB88320U ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFU;
  for (const std::uint8_t b : bytes) c = table[(c ^ b) & 0xFFU] ^ (c >> 8);
  return c ^ 0xFFFFFFFFU;
}

std::vector<std::uint8_t> png_with_resolution(std::span<const std::uint8_t> png, double dpi) {
  check_dpi(dpi);
  static constexpr std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (png.size() < 33 || std::memcmp(png.data(), signature, 8) != 0 || std::memcmp(png.data() + 12, "IHDR", 4) != 0) {
    throw Error("cannot set the resolution: the bytes are not a PNG file");
  }
  std::vector<std::uint8_t> chunk{'p', 'H', 'Y', 's'};
  const auto ppm = static_cast<std::uint32_t>(std::llround(dpi / 0.0254));
  put_be32(chunk, ppm);
  put_be32(chunk, ppm);
  chunk.push_back(1);  // unit: metre
  const std::uint32_t crc = crc32(chunk);

  std::vector<std::uint8_t> out(png.begin(), png.begin() + 33);  // signature + IHDR (13 data bytes)
  put_be32(out, 9);
  out.insert(out.end(), chunk.begin(), chunk.end());
  put_be32(out, crc);
  for (std::size_t offset = 33; offset + 12 <= png.size();) {
    const std::size_t length = get_be32(png.data() + offset);
    const std::size_t end = std::min(png.size(), offset + 12 + length);
    if (std::memcmp(png.data() + offset + 4, "pHYs", 4) != 0) {
      out.insert(out.end(), png.begin() + static_cast<std::ptrdiff_t>(offset), png.begin() + static_cast<std::ptrdiff_t>(end));
    }
    offset = end;
  }
  return out;
}

std::vector<std::uint8_t> jpeg_with_resolution(std::span<const std::uint8_t> jpeg, double dpi) {
  check_dpi(dpi);
  if (jpeg.size() < 4 || jpeg[0] != 0xFF || jpeg[1] != 0xD8) throw Error("cannot set the resolution: the bytes are not a JPEG file");
  const auto density = static_cast<std::uint16_t>(std::lround(dpi));
  std::vector<std::uint8_t> out(jpeg.begin(), jpeg.end());
  if (out.size() >= 20 && out[2] == 0xFF && out[3] == 0xE0 && std::memcmp(&out[6], "JFIF\0", 5) == 0) {
    out[13] = 1;  // units: dots per inch
    out[14] = out[16] = static_cast<std::uint8_t>(density >> 8);
    out[15] = out[17] = static_cast<std::uint8_t>(density & 0xFF);
    return out;
  }
  const std::uint8_t app0[18] = {0xFF, 0xE0, 0, 16, 'J', 'F', 'I', 'F', 0, 1, 1, 1,
                                 static_cast<std::uint8_t>(density >> 8), static_cast<std::uint8_t>(density & 0xFF),
                                 static_cast<std::uint8_t>(density >> 8), static_cast<std::uint8_t>(density & 0xFF), 0, 0};
  out.insert(out.begin() + 2, std::begin(app0), std::end(app0));
  return out;
}

}  // namespace stiffpath::vision
