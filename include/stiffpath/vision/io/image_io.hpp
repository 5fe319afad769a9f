// Reading scans (PNG, TIFF, JPEG; grey or colour; 8 or 16 bit) with their resolution, and writing images atomically.
#pragma once

#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace stiffpath::vision {

//! A scan ready for analysis.
struct ScanImage {
  cv::Mat grey;             //!< one channel, CV_8U or CV_16U (colour scans are converted to grey)
  double dpi = 1200;        //!< resolution used (dots per inch, equal along x and y)
  std::string dpi_source;   //!< "PNG pHYs", "TIFF XResolution", "JPEG JFIF", "JPEG Exif", "--dpi" or "default"
  std::vector<std::string> warnings;  //!< e.g. the resolution was assumed
};

//! Loads a scan. The resolution is `dpi_override` when given, else the file's metadata (see
//! read_resolution), else `default_dpi` with a warning. Throws stiffpath::Error naming the file when
//! it is missing, empty, not a readable image, has no pixels, has a pixel type other than 8/16-bit
//! integer, or stores different x and y resolutions (and no override is given).
ScanImage load_scan(const std::filesystem::path& path, std::optional<double> dpi_override = std::nullopt,
                    double default_dpi = 1200.0);

//! Encodes an image for the file's extension (.png, .tif/.tiff, .jpg/.jpeg) with `dpi` stored in
//! its metadata. Throws stiffpath::Error for another extension or a failed encoding.
std::vector<std::uint8_t> encode_image(const cv::Mat& image, const std::filesystem::path& path, double dpi);

//! encode_image, then writes the bytes through core::AtomicFile (no half-written file on failure).
void write_image(const std::filesystem::path& path, const cv::Mat& image, double dpi);

//! Writes a PNG band by band as its rows come (for images too large to hold twice in memory), with
//! `dpi` in its pHYs chunk, through core::AtomicFile: the file appears only after commit().
class PngRowWriter {
 public:
  //! Starts the file: width × height pixels of OpenCV `type` CV_8UC1, CV_16UC1, CV_8UC3 or CV_16UC3
  //! (BGR). Throws stiffpath::Error naming the file for anything else or a file that cannot be created.
  PngRowWriter(const std::filesystem::path& path, int width, int height, int type, double dpi);
  ~PngRowWriter();
  PngRowWriter(const PngRowWriter&) = delete;
  PngRowWriter& operator=(const PngRowWriter&) = delete;
  //! The next rows, top to bottom (`type`, width columns). Throws on a mismatch or a write error.
  void write(const cv::Mat& rows);
  //! After the last row: ends the PNG and renames the file into place. Throws if rows are missing.
  void commit();

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace stiffpath::vision
