// Scan loading (OpenCV decoding + our own resolution parsing) and atomic image writing with the resolution stored.
#include "stiffpath/vision/io/image_io.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/io/resolution.hpp"

namespace stiffpath::vision {

namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void check_dpi(double dpi, const SourceLocation& where, const char* what) {
  if (!(dpi >= kMinScanDpi) || !(dpi <= kMaxScanDpi)) {
    throw Error(where, fmt::format("{} must be a resolution of {} to {} dpi, got {}", what, kMinScanDpi, kMaxScanDpi, dpi));
  }
}

// The size a PNG declares in its IHDR chunk, checked before decoding (the decoder would refuse it
// without naming it, or try to allocate it). Limits as OpenCV's: 2^20 pixels per side, 2^30 in all.
void check_declared_size(const std::filesystem::path& path, const SourceLocation& where) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[24] = {};
  in.read(reinterpret_cast<char*>(h), sizeof h);
  if (in.gcount() != 24 || std::memcmp(h, "\x89PNG\r\n\x1a\n", 8) != 0) return;
  const auto be32 = [&h](int at) {
    return (std::uint64_t{h[at]} << 24) | (std::uint64_t{h[at + 1]} << 16) | (std::uint64_t{h[at + 2]} << 8) | h[at + 3];
  };
  const std::uint64_t width = be32(16), height = be32(20);
  constexpr std::uint64_t max_side = std::uint64_t{1} << 20, max_pixels = std::uint64_t{1} << 30;
  if (width > max_side || height > max_side || width * height > max_pixels) {
    throw Error(where, fmt::format("RANGE: the PNG declares {} × {} pixels; a scan may have at most {} per side and {} "
                                   "in all",
                                   width, height, max_side, max_pixels));
  }
}

}  // namespace

ScanImage load_scan(const std::filesystem::path& path, std::optional<double> dpi_override, double default_dpi) {
  const SourceLocation where{path.string(), 0, 0};
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(where, "no such file");
  if (std::filesystem::file_size(path, ec) == 0) throw Error(where, "the file is empty (0 bytes), not an image");
  check_declared_size(path, where);
  // Grey straight from the decoder (a colour scan is never held in colour), at its own bit depth.
  cv::Mat raw;
  try {
    raw = cv::imread(path.string(), cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
  } catch (const cv::Exception& e) {
    throw Error(where, std::string("not a readable image: ") + e.what());
  }
  if (raw.empty()) throw Error(where, "not a readable image (PNG, TIFF or JPEG expected)");
  if (raw.rows < 1 || raw.cols < 1) throw Error(where, "the image has no pixels");

  ScanImage scan;
  const int channels = raw.channels();
  if (raw.depth() != CV_8U && raw.depth() != CV_16U) {
    throw Error(where, fmt::format("unsupported pixel type (depth code {}): 8- or 16-bit integer images expected", raw.depth()));
  }
  if (channels == 1) {
    scan.grey = raw;
  } else if (channels == 3) {
    cv::cvtColor(raw, scan.grey, cv::COLOR_BGR2GRAY);
  } else if (channels == 4) {
    cv::cvtColor(raw, scan.grey, cv::COLOR_BGRA2GRAY);
  } else {
    throw Error(where, fmt::format("unsupported number of channels: {}", channels));
  }

  if (dpi_override) {
    check_dpi(*dpi_override, where, "--dpi");
    scan.dpi = *dpi_override;
    scan.dpi_source = "--dpi";
    return scan;
  }
  check_dpi(default_dpi, where, "default resolution");
  const StoredResolution res = read_stored_resolution(path);
  if (res.kind == StoredResolution::Kind::value) {
    // A stored density is used only within the resolutions a scan can have: outside, it is a wrong scale
    // (a 1 px/m PNG would make a 0.2 mm mark 9 m wide), so the scan is refused rather than measured with it.
    for (const double dpi : {res.dpi_x, res.dpi_y}) {
      if (!(dpi >= kMinScanDpi) || !(dpi <= kMaxScanDpi)) {
        throw Error(where, fmt::format("RANGE: the file's {} stores {} ({:.6g} dpi), outside the {} to {} dpi a scan can have: "
                                       "its resolution is unknown; pass --dpi to give it",
                                       res.source, res.stored, dpi, kMinScanDpi, kMaxScanDpi));
      }
    }
    if (std::abs(res.dpi_x - res.dpi_y) > 1e-6 * res.dpi_x) {
      throw Error(where, fmt::format("the {} metadata gives different resolutions along x ({} dpi) and y ({} dpi), {}; "
                                     "non-square pixels are not supported: resample the scan or pass --dpi",
                                     res.source, res.dpi_x, res.dpi_y, res.stored));
    }
    scan.dpi = res.dpi_x;
    scan.dpi_source = res.source;
    if (scan.dpi < 300.0) {
      scan.warnings.push_back(fmt::format("the file's metadata ({}) says {} dpi, low for a scan of a laser mark; "
                                          "pass --dpi if it is wrong", res.source, scan.dpi));
    }
    return scan;
  }
  scan.dpi = default_dpi;
  scan.dpi_source = "default";
  if (res.kind == StoredResolution::Kind::aspect_only) {
    scan.warnings.push_back(fmt::format("the file's {} stores only {}, no resolution; assumed {} dpi (pass --dpi to set it)",
                                        res.source, res.stored, default_dpi));
  } else {
    scan.warnings.push_back(fmt::format("the file stores no resolution; assumed {} dpi (pass --dpi to set it)", default_dpi));
  }
  return scan;
}

std::vector<std::uint8_t> encode_image(const cv::Mat& image, const std::filesystem::path& path, double dpi) {
  const std::string ext = lower_extension(path);
  const SourceLocation where{path.string(), 0, 0};
  std::vector<int> params;
  const bool tiff = ext == ".tif" || ext == ".tiff";
  const bool jpeg = ext == ".jpg" || ext == ".jpeg";
  if (ext != ".png" && !tiff && !jpeg) throw Error(where, "unsupported image extension: use .png, .tif, .tiff, .jpg or .jpeg");
  if (tiff) {
    const int whole = static_cast<int>(std::lround(dpi));
    params = {cv::IMWRITE_TIFF_RESUNIT, 2, cv::IMWRITE_TIFF_XDPI, whole, cv::IMWRITE_TIFF_YDPI, whole};
  }
  if (jpeg) params = {cv::IMWRITE_JPEG_QUALITY, 95};
  std::vector<std::uint8_t> bytes;
  if (!cv::imencode(ext, image, bytes, params) || bytes.empty()) throw Error(where, "the image could not be encoded");
  if (ext == ".png") return png_with_resolution(bytes, dpi);
  if (jpeg) return jpeg_with_resolution(bytes, dpi);
  return bytes;
}

void write_image(const std::filesystem::path& path, const cv::Mat& image, double dpi) {
  if (lower_extension(path) == ".png" && !image.empty()) {
    // Row by row: no encoded copy of the whole image in memory.
    PngRowWriter png(path, image.cols, image.rows, image.type(), dpi);
    for (int y = 0; y < image.rows; y += 256) png.write(image.rowRange(y, std::min(image.rows, y + 256)));
    png.commit();
    return;
  }
  const std::vector<std::uint8_t> bytes = encode_image(image, path, dpi);
  core::AtomicFile file(path);
  file.stream().write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

}  // namespace stiffpath::vision
