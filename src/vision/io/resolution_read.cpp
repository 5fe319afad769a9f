// Reading the resolution from PNG pHYs, TIFF (XResolution/YResolution/ResolutionUnit) and JPEG JFIF or Exif bytes.
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>

#include "stiffpath/vision/io/resolution.hpp"

namespace stiffpath::vision {

namespace {

constexpr double kMetresPerInch = 0.0254;

// Random access to the file's bytes: fills `out` from `offset`, false if the bytes are not there.
using ReadAt = std::function<bool(std::uint64_t offset, std::size_t n, std::uint8_t* out)>;

std::uint32_t be32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}
std::uint16_t be16(const std::uint8_t* p) { return static_cast<std::uint16_t>((p[0] << 8) | p[1]); }

std::optional<Resolution> make(double dpi_x, double dpi_y, const char* source) {
  if (!(dpi_x > 0.0) || !(dpi_y > 0.0) || !std::isfinite(dpi_x) || !std::isfinite(dpi_y) || dpi_x > 1e6 || dpi_y > 1e6) {
    return std::nullopt;
  }
  return Resolution{dpi_x, dpi_y, source};
}

// A whole number of dpi whose rounding to pixels per metre gives the stored value is taken as exact.
double dpi_from_ppm(std::uint32_t ppm) {
  const double dpi = ppm * kMetresPerInch;
  const double whole = std::round(dpi);
  return std::llround(whole / kMetresPerInch) == static_cast<long long>(ppm) ? whole : dpi;
}

std::optional<Resolution> parse_png(const ReadAt& read) {
  std::uint64_t offset = 8;
  std::uint8_t head[8];
  for (int chunk = 0; chunk < 10000 && read(offset, 8, head); ++chunk) {
    const std::uint32_t length = be32(head);
    if (std::memcmp(head + 4, "pHYs", 4) == 0 && length == 9) {
      std::uint8_t data[9];
      if (!read(offset + 8, 9, data) || data[8] != 1) return std::nullopt;  // unit 0: aspect ratio only
      return make(dpi_from_ppm(be32(data)), dpi_from_ppm(be32(data + 4)), "PNG pHYs");
    }
    if (std::memcmp(head + 4, "IDAT", 4) == 0 || std::memcmp(head + 4, "IEND", 4) == 0) break;
    offset += 12ULL + length;
  }
  return std::nullopt;
}

std::optional<Resolution> parse_tiff(const ReadAt& read, const char* source) {
  std::uint8_t header[8];
  if (!read(0, 8, header)) return std::nullopt;
  const bool little = header[0] == 'I';
  auto u16 = [little](const std::uint8_t* p) { return little ? static_cast<std::uint16_t>(p[0] | (p[1] << 8)) : be16(p); };
  auto u32 = [little](const std::uint8_t* p) {
    return little ? (std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24))
                  : be32(p);
  };
  if (u16(header + 2) != 42) return std::nullopt;  // 43 is BigTIFF: not read
  const std::uint32_t ifd = u32(header + 4);
  std::uint8_t count_bytes[2];
  if (!read(ifd, 2, count_bytes)) return std::nullopt;
  const std::uint16_t count = u16(count_bytes);
  double xres = 0.0, yres = 0.0;
  int unit = 2;  // TIFF 6.0: ResolutionUnit defaults to inch
  for (std::uint16_t i = 0; i < count; ++i) {
    std::uint8_t entry[12];
    if (!read(ifd + 2ULL + 12ULL * i, 12, entry)) return std::nullopt;
    const std::uint16_t tag = u16(entry), type = u16(entry + 2);
    if ((tag == 282 || tag == 283) && type == 5) {
      std::uint8_t rational[8];
      if (!read(u32(entry + 8), 8, rational) || u32(rational + 4) == 0) continue;
      (tag == 282 ? xres : yres) = static_cast<double>(u32(rational)) / u32(rational + 4);
    } else if (tag == 296 && type == 3) {
      unit = u16(entry + 8);
    }
  }
  if (yres == 0.0) yres = xres;
  if (unit == 3) return make(xres * 2.54, yres * 2.54, source);
  if (unit == 2) return make(xres, yres, source);
  return std::nullopt;  // unit 1: no absolute unit
}

std::optional<Resolution> parse_jpeg(const ReadAt& read) {
  std::uint64_t offset = 2;
  std::uint8_t marker[4];
  std::optional<Resolution> exif;
  for (int segment = 0; segment < 1000 && read(offset, 4, marker); ++segment) {
    if (marker[0] != 0xFF || marker[1] == 0xDA || marker[1] == 0xD9) break;  // SOS or EOI: no more headers
    const std::uint16_t length = be16(marker + 2);
    if (length < 2) break;
    std::vector<std::uint8_t> data(length - 2u);
    if (!read(offset + 4, data.size(), data.data())) break;
    if (marker[1] == 0xE0 && data.size() >= 12 && std::memcmp(data.data(), "JFIF\0", 5) == 0) {
      const int units = data[7];
      const double x = be16(&data[8]), y = be16(&data[10]);
      if (units == 1) return make(x, y, "JPEG JFIF");
      if (units == 2) return make(x * 2.54, y * 2.54, "JPEG JFIF");
    } else if (marker[1] == 0xE1 && data.size() > 14 && std::memcmp(data.data(), "Exif\0\0", 6) == 0 && !exif) {
      const std::span<const std::uint8_t> tiff(data.data() + 6, data.size() - 6);
      exif = parse_tiff(
          [tiff](std::uint64_t off, std::size_t n, std::uint8_t* out) {
            if (off + n > tiff.size()) return false;
            std::memcpy(out, tiff.data() + off, n);
            return true;
          },
          "JPEG Exif");
    }
    offset += 2ULL + length;
  }
  return exif;
}

std::optional<Resolution> parse(const ReadAt& read) {
  std::uint8_t magic[8];
  if (!read(0, 8, magic)) return std::nullopt;
  static constexpr std::uint8_t png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (std::memcmp(magic, png_signature, 8) == 0) return parse_png(read);
  if ((magic[0] == 'I' && magic[1] == 'I') || (magic[0] == 'M' && magic[1] == 'M')) return parse_tiff(read, "TIFF XResolution");
  if (magic[0] == 0xFF && magic[1] == 0xD8) return parse_jpeg(read);
  return std::nullopt;
}

}  // namespace

std::optional<Resolution> resolution_from_memory(std::span<const std::uint8_t> bytes) {
  return parse([bytes](std::uint64_t off, std::size_t n, std::uint8_t* out) {
    if (off > bytes.size() || n > bytes.size() - off) return false;
    if (n > 0) std::memcpy(out, bytes.data() + off, n);  // an empty segment may come with a null `out`
    return true;
  });
}

std::optional<Resolution> read_resolution(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return parse([&in](std::uint64_t off, std::size_t n, std::uint8_t* out) {
    in.clear();
    in.seekg(static_cast<std::streamoff>(off));
    in.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
    return in.gcount() == static_cast<std::streamsize>(n);
  });
}

}  // namespace stiffpath::vision
