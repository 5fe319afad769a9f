// Reading the resolution from PNG pHYs, TIFF (XResolution/YResolution/ResolutionUnit) and JPEG JFIF or Exif bytes.
#include <cmath>
#include <cstring>
#include <fmt/format.h>
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

using Kind = StoredResolution::Kind;

// A whole number of dpi whose rounding to pixels per metre gives the stored value is taken as exact.
double dpi_from_ppm(std::uint32_t ppm) {
  const double dpi = ppm * kMetresPerInch;
  const double whole = std::round(dpi);
  return std::llround(whole / kMetresPerInch) == static_cast<long long>(ppm) ? whole : dpi;
}

StoredResolution value(double dpi_x, double dpi_y, const char* source, std::string stored) {
  return {Kind::value, dpi_x, dpi_y, source, std::move(stored)};
}
StoredResolution aspect(const char* source, std::string stored) { return {Kind::aspect_only, 0.0, 0.0, source, std::move(stored)}; }

StoredResolution parse_png(const ReadAt& read) {
  std::uint64_t offset = 8;
  std::uint8_t head[8];
  for (int chunk = 0; chunk < 10000 && read(offset, 8, head); ++chunk) {
    const std::uint32_t length = be32(head);
    if (std::memcmp(head + 4, "pHYs", 4) == 0 && length == 9) {
      std::uint8_t data[9];
      if (!read(offset + 8, 9, data)) return {};
      const std::uint32_t x = be32(data), y = be32(data + 4);
      if (data[8] != 1) return aspect("PNG pHYs", fmt::format("a pixel aspect ratio {}:{} (unit {})", x, y, data[8]));
      return value(dpi_from_ppm(x), dpi_from_ppm(y), "PNG pHYs", fmt::format("{} × {} px/m", x, y));
    }
    if (std::memcmp(head + 4, "IDAT", 4) == 0 || std::memcmp(head + 4, "IEND", 4) == 0) break;
    offset += 12ULL + length;
  }
  return {};
}

StoredResolution parse_tiff(const ReadAt& read, const char* source) {
  std::uint8_t header[8];
  if (!read(0, 8, header)) return {};
  const bool little = header[0] == 'I';
  auto u16 = [little](const std::uint8_t* p) { return little ? static_cast<std::uint16_t>(p[0] | (p[1] << 8)) : be16(p); };
  auto u32 = [little](const std::uint8_t* p) {
    return little ? (std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24))
                  : be32(p);
  };
  if (u16(header + 2) != 42) return {};  // 43 is BigTIFF: not read
  const std::uint32_t ifd = u32(header + 4);
  std::uint8_t count_bytes[2];
  if (!read(ifd, 2, count_bytes)) return {};
  const std::uint16_t count = u16(count_bytes);
  double xres = 0.0, yres = 0.0;
  std::string xtext, ytext;  // the rationals as stored
  int unit = 2;  // TIFF 6.0: ResolutionUnit defaults to inch
  for (std::uint16_t i = 0; i < count; ++i) {
    std::uint8_t entry[12];
    if (!read(ifd + 2ULL + 12ULL * i, 12, entry)) return {};
    const std::uint16_t tag = u16(entry), type = u16(entry + 2);
    if ((tag == 282 || tag == 283) && type == 5) {
      std::uint8_t rational[8];
      if (!read(u32(entry + 8), 8, rational)) continue;
      const std::uint32_t num = u32(rational), den = u32(rational + 4);
      (tag == 282 ? xtext : ytext) = fmt::format("{}/{}", num, den);
      (tag == 282 ? xres : yres) = den == 0 ? 0.0 : static_cast<double>(num) / den;  // n/0 defines no density
    } else if (tag == 296 && type == 3) {
      unit = u16(entry + 8);
    }
  }
  if (xtext.empty()) return {};
  if (ytext.empty()) yres = xres, ytext = xtext;
  if (unit == 3) return value(xres * 2.54, yres * 2.54, source, fmt::format("{} × {} pixels per centimetre", xtext, ytext));
  if (unit == 2) return value(xres, yres, source, fmt::format("{} × {} pixels per inch", xtext, ytext));
  return aspect(source, fmt::format("a density of {} × {} in no absolute unit (ResolutionUnit {})", xtext, ytext, unit));
}

StoredResolution parse_jpeg(const ReadAt& read) {
  std::uint64_t offset = 2;
  std::uint8_t marker[4];
  StoredResolution exif;
  for (int segment = 0; segment < 1000 && read(offset, 4, marker); ++segment) {
    if (marker[0] != 0xFF || marker[1] == 0xDA || marker[1] == 0xD9) break;  // SOS or EOI: no more headers
    const std::uint16_t length = be16(marker + 2);
    if (length < 2) break;
    std::vector<std::uint8_t> data(length - 2u);
    if (!read(offset + 4, data.size(), data.data())) break;
    if (marker[1] == 0xE0 && data.size() >= 12 && std::memcmp(data.data(), "JFIF\0", 5) == 0) {
      const int units = data[7];
      const int x = be16(&data[8]), y = be16(&data[10]);
      if (units == 1) return value(x, y, "JPEG JFIF", fmt::format("{} × {} dots per inch", x, y));
      if (units == 2) return value(x * 2.54, y * 2.54, "JPEG JFIF", fmt::format("{} × {} dots per centimetre", x, y));
      if (exif.kind == Kind::none) exif = aspect("JPEG JFIF", fmt::format("a pixel aspect ratio {}:{} (units {})", x, y, units));
    } else if (marker[1] == 0xE1 && data.size() > 14 && std::memcmp(data.data(), "Exif\0\0", 6) == 0 && exif.kind != Kind::value) {
      const std::span<const std::uint8_t> tiff(data.data() + 6, data.size() - 6);
      StoredResolution found = parse_tiff(
          [tiff](std::uint64_t off, std::size_t n, std::uint8_t* out) {
            if (off + n > tiff.size()) return false;
            std::memcpy(out, tiff.data() + off, n);
            return true;
          },
          "JPEG Exif");
      if (found.kind != Kind::none) exif = std::move(found);
    }
    offset += 2ULL + length;
  }
  return exif;
}

StoredResolution parse(const ReadAt& read) {
  std::uint8_t magic[8];
  if (!read(0, 8, magic)) return {};
  static constexpr std::uint8_t png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (std::memcmp(magic, png_signature, 8) == 0) return parse_png(read);
  if ((magic[0] == 'I' && magic[1] == 'I') || (magic[0] == 'M' && magic[1] == 'M')) return parse_tiff(read, "TIFF XResolution");
  if (magic[0] == 0xFF && magic[1] == 0xD8) return parse_jpeg(read);
  return {};
}

// The resolution as the old readers gave it: an absolute, positive, finite density of at most 1e6 dpi.
std::optional<Resolution> usable(const StoredResolution& s) {
  if (s.kind != Kind::value) return std::nullopt;
  if (!(s.dpi_x > 0.0) || !(s.dpi_y > 0.0) || !std::isfinite(s.dpi_x) || !std::isfinite(s.dpi_y) || s.dpi_x > 1e6 || s.dpi_y > 1e6) {
    return std::nullopt;
  }
  return Resolution{s.dpi_x, s.dpi_y, s.source};
}

}  // namespace

StoredResolution stored_resolution_from_memory(std::span<const std::uint8_t> bytes) {
  return parse([bytes](std::uint64_t off, std::size_t n, std::uint8_t* out) {
    if (off > bytes.size() || n > bytes.size() - off) return false;
    if (n > 0) std::memcpy(out, bytes.data() + off, n);  // an empty segment may come with a null `out`
    return true;
  });
}

StoredResolution read_stored_resolution(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  return parse([&in](std::uint64_t off, std::size_t n, std::uint8_t* out) {
    in.clear();
    in.seekg(static_cast<std::streamoff>(off));
    in.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
    return in.gcount() == static_cast<std::streamsize>(n);
  });
}

std::optional<Resolution> resolution_from_memory(std::span<const std::uint8_t> bytes) {
  return usable(stored_resolution_from_memory(bytes));
}

std::optional<Resolution> read_resolution(const std::filesystem::path& path) { return usable(read_stored_resolution(path)); }

}  // namespace stiffpath::vision
