// Scan resolution (dots per inch) from the image file's own metadata: PNG pHYs, TIFF XResolution, JPEG JFIF/Exif.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace stiffpath::vision {

//! Resolution found in an image file. OpenCV does not expose it, so the bytes are parsed here.
struct Resolution {
  double dpi_x = 0;    //!< dots per inch along x (columns)
  double dpi_y = 0;    //!< dots per inch along y (rows)
  std::string source;  //!< where it came from: "PNG pHYs", "TIFF XResolution", "JPEG JFIF" or "JPEG Exif"
};

//! The resolutions a scan may have (dpi): below, a pixel is wider than 2.5 mm; above, smaller than 0.25 µm. A
//! file whose metadata says something outside is refused by load_scan (pass --dpi), never measured with it.
inline constexpr double kMinScanDpi = 10.0;
inline constexpr double kMaxScanDpi = 100000.0;

//! What an image file's metadata says about its resolution, whatever it is (for messages that say so).
struct StoredResolution {
  enum class Kind {
    none,         //!< the file stores nothing about it (or is not a PNG, TIFF or JPEG, or cannot be read)
    aspect_only,  //!< only the pixels' aspect ratio: PNG pHYs unit 0, TIFF ResolutionUnit 1, JPEG JFIF units 0
    value,        //!< a density in an absolute unit: dpi_x and dpi_y hold it, converted, whatever its size
  };
  Kind kind = Kind::none;
  double dpi_x = 0, dpi_y = 0;  //!< for Kind::value: the stored densities in dpi (0 for a zero or undefined one)
  std::string source;           //!< "PNG pHYs", "TIFF XResolution", "JPEG JFIF" or "JPEG Exif" (empty for none)
  std::string stored;           //!< the stored values in the file's own unit, e.g. "1 × 1 px/m", "0 × 0 dots per inch"
};

//! Parses what a whole file held in memory stores about its resolution.
StoredResolution stored_resolution_from_memory(std::span<const std::uint8_t> bytes);
//! The same for a file on disk, reading only the parts it needs (the TIFF directory may sit at the end of
//! the file); Kind::none when it cannot be read.
StoredResolution read_stored_resolution(const std::filesystem::path& path);

//! Parses the resolution from a whole file held in memory. nullopt when the format is not PNG,
//! TIFF or JPEG, when the file stores no resolution or only an aspect ratio (unit "unknown"), or
//! when the stored value is not a positive finite number. A PNG's integer pixels-per-metre that is
//! the rounding of a whole number of dpi is read as that whole number (47244 px/m → 1200 dpi).
std::optional<Resolution> resolution_from_memory(std::span<const std::uint8_t> bytes);

//! The same for a file on disk, reading only the parts it needs (the TIFF directory may sit at the
//! end of the file). nullopt too when the file cannot be read.
std::optional<Resolution> read_resolution(const std::filesystem::path& path);

//! Returns a copy of a PNG file with its pHYs chunk set to `dpi` in both directions (pixels per
//! metre, unit metre), inserted after IHDR or replacing an existing one. Throws stiffpath::Error if
//! the bytes are not a PNG.
std::vector<std::uint8_t> png_with_resolution(std::span<const std::uint8_t> png, double dpi);

//! Returns a copy of a JPEG file whose JFIF header says `dpi` (units = dots per inch, the density
//! rounded to a whole number ≤ 65535), adding a JFIF APP0 segment when there is none. Throws
//! stiffpath::Error if the bytes are not a JPEG.
std::vector<std::uint8_t> jpeg_with_resolution(std::span<const std::uint8_t> jpeg, double dpi);

//! CRC-32 (ISO 3309, as used by PNG chunks) of the bytes.
std::uint32_t crc32(std::span<const std::uint8_t> bytes);

}  // namespace stiffpath::vision
