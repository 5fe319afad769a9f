// Tests of reading and writing the scan resolution in PNG, TIFF and JPEG bytes, hand-built files included.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "cli_runner.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/vision/io/resolution.hpp"

namespace stiffpath::vision {
namespace {

cv::Mat small_image() {
  cv::Mat m(8, 12, CV_8U, cv::Scalar(200));
  m.at<std::uint8_t>(3, 4) = 10;
  return m;
}

std::vector<std::uint8_t> encoded(const char* ext) {
  std::vector<std::uint8_t> bytes;
  cv::imencode(ext, small_image(), bytes);
  return bytes;
}

TEST(Resolution, Crc32MatchesTheStandardCheckValue) {
  const char* text = "123456789";
  EXPECT_EQ(crc32({reinterpret_cast<const std::uint8_t*>(text), 9}), 0xCBF43926U);
}

TEST(Resolution, PngPhysRoundTripsAndReadsWholeDpi) {
  const auto png = png_with_resolution(encoded(".png"), 1200);
  const auto r = resolution_from_memory(png);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->dpi_x, 1200.0);  // 47244 px/m is the rounding of 1200 dpi, read back as exactly 1200
  EXPECT_EQ(r->source, "PNG pHYs");
  // The image still decodes (chunk CRC and order valid) and setting twice keeps one pHYs chunk.
  const auto twice = png_with_resolution(png, 600);
  EXPECT_EQ(twice.size(), png.size());
  EXPECT_EQ(resolution_from_memory(twice)->dpi_y, 600.0);
  const cv::Mat back = cv::imdecode(twice, cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(back.empty());
  EXPECT_EQ(back.at<std::uint8_t>(3, 4), 10);
}

TEST(Resolution, PngWithoutPhysOrWithAspectOnlyHasNone) {
  auto png = encoded(".png");
  EXPECT_FALSE(resolution_from_memory(png).has_value());
  auto aspect = png_with_resolution(png, 300);
  // Unit byte of pHYs (right after IHDR: 8 + 25 bytes, then length, type, 8 data bytes) set to 0 = unknown.
  aspect[33 + 8 + 8] = 0;
  EXPECT_FALSE(resolution_from_memory(aspect).has_value());
}

TEST(Resolution, TiffWrittenByOpenCvAndHandBuiltBigEndianInCentimetres) {
  const auto tiff = encode_image(small_image(), "x.tif", 2400);
  const auto r = resolution_from_memory(tiff);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->dpi_x, 2400.0, 1e-9);
  EXPECT_EQ(r->source, "TIFF XResolution");

  // Big-endian TIFF, one IFD with XResolution = 472/1 and YResolution = 236/1 per cm, unit 3 (cm).
  std::vector<std::uint8_t> b = {'M', 'M', 0, 42, 0, 0, 0, 8,  // header, IFD at 8
                                 0, 3,                          // 3 entries
                                 0x01, 0x1A, 0, 5, 0, 0, 0, 1, 0, 0, 0, 50,   // XResolution → offset 50
                                 0x01, 0x1B, 0, 5, 0, 0, 0, 1, 0, 0, 0, 58,   // YResolution → offset 58
                                 0x01, 0x28, 0, 3, 0, 0, 0, 1, 0, 3, 0, 0,    // ResolutionUnit = 3
                                 0, 0, 0, 0};                                 // next IFD
  b.resize(50);
  for (const std::uint32_t v : {472u, 1u, 236u, 1u}) {
    for (int shift = 24; shift >= 0; shift -= 8) b.push_back(static_cast<std::uint8_t>(v >> shift));
  }
  const auto hand = resolution_from_memory(b);
  ASSERT_TRUE(hand.has_value());
  EXPECT_NEAR(hand->dpi_x, 472 * 2.54, 1e-9);
  EXPECT_NEAR(hand->dpi_y, 236 * 2.54, 1e-9);
}

TEST(Resolution, JpegJfifDensityAndExifFallback) {
  const auto jpeg = jpeg_with_resolution(encoded(".jpg"), 1200);
  const auto r = resolution_from_memory(jpeg);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->dpi_x, 1200.0);
  EXPECT_EQ(r->source, "JPEG JFIF");
  ASSERT_FALSE(cv::imdecode(jpeg, cv::IMREAD_UNCHANGED).empty());

  // SOI, an APP1 Exif segment holding a little-endian TIFF with XResolution 300/1 (no unit: inch), EOI.
  std::vector<std::uint8_t> tiff = {'I', 'I', 42, 0, 8, 0, 0, 0, 1, 0, 0x1A, 0x01, 5, 0, 1, 0, 0, 0, 26, 0, 0, 0, 0, 0, 0, 0,
                                    44, 1, 0, 0, 1, 0, 0, 0};
  std::vector<std::uint8_t> j = {0xFF, 0xD8, 0xFF, 0xE1, 0, static_cast<std::uint8_t>(2 + 6 + tiff.size()), 'E', 'x', 'i', 'f', 0, 0};
  j.insert(j.end(), tiff.begin(), tiff.end());
  j.insert(j.end(), {0xFF, 0xD9});
  const auto exif = resolution_from_memory(j);
  ASSERT_TRUE(exif.has_value());
  EXPECT_EQ(exif->dpi_x, 300.0);
  EXPECT_EQ(exif->source, "JPEG Exif");
}

TEST(Resolution, GarbageAndTruncatedFilesHaveNoResolution) {
  const std::string text = "not an image at all";
  EXPECT_FALSE(resolution_from_memory({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}).has_value());
  auto png = png_with_resolution(encoded(".png"), 1200);
  png.resize(40);  // cut inside the pHYs chunk
  EXPECT_FALSE(resolution_from_memory(png).has_value());
  const std::vector<std::uint8_t> tiff_bad_offset = {'I', 'I', 42, 0, 0xFF, 0xFF, 0, 0};
  EXPECT_FALSE(resolution_from_memory(tiff_bad_offset).has_value());
  EXPECT_THROW(png_with_resolution({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, 1200), Error);
  EXPECT_THROW(png_with_resolution(encoded(".png"), -5), Error);
}

TEST(Resolution, LoadScanUsesMetadataOverrideOrDefault) {
  test::TempDir dir;
  write_image(dir / "a.png", small_image(), 600);
  const ScanImage meta = load_scan(dir / "a.png");
  EXPECT_EQ(meta.dpi, 600.0);
  EXPECT_EQ(meta.dpi_source, "PNG pHYs");
  EXPECT_TRUE(meta.warnings.empty());
  const ScanImage forced = load_scan(dir / "a.png", 1200.0);
  EXPECT_EQ(forced.dpi, 1200.0);
  EXPECT_EQ(forced.dpi_source, "--dpi");
  cv::imwrite((dir / "b.png").string(), small_image());
  const ScanImage fallback = load_scan(dir / "b.png");
  EXPECT_EQ(fallback.dpi, 1200.0);
  EXPECT_EQ(fallback.dpi_source, "default");
  ASSERT_EQ(fallback.warnings.size(), 1u);
  write_image(dir / "c.jpg", small_image(), 150);
  EXPECT_EQ(load_scan(dir / "c.jpg").dpi, 150.0);
  EXPECT_EQ(load_scan(dir / "c.jpg").warnings.size(), 1u);  // suspiciously low for a scan
}

// A PNG whose pHYs chunk stores these raw values (px per unit, unit 1 = metre, 0 = aspect ratio only).
std::vector<std::uint8_t> png_storing(std::uint32_t x, std::uint32_t y, std::uint8_t unit) {
  auto png = png_with_resolution(encoded(".png"), 300);
  const std::size_t data = 33 + 8;  // pHYs right after IHDR: length and type, then its 9 data bytes
  EXPECT_EQ(std::memcmp(&png[33 + 4], "pHYs", 4), 0);
  for (int k = 0; k < 4; ++k) {
    png[data + k] = static_cast<std::uint8_t>(x >> (24 - 8 * k));
    png[data + 4 + k] = static_cast<std::uint8_t>(y >> (24 - 8 * k));
  }
  png[data + 8] = unit;
  const std::uint32_t crc = crc32({&png[33 + 4], 4 + 9});
  for (int k = 0; k < 4; ++k) png[data + 9 + k] = static_cast<std::uint8_t>(crc >> (24 - 8 * k));
  EXPECT_FALSE(cv::imdecode(png, cv::IMREAD_UNCHANGED).empty());  // still a valid PNG
  return png;
}

TEST(Resolution, StoredResolutionSaysWhatTheFileStoresWhateverItIs) {
  const StoredResolution one = stored_resolution_from_memory(png_storing(1, 1, 1));
  EXPECT_EQ(one.kind, StoredResolution::Kind::value);
  EXPECT_NEAR(one.dpi_x, 0.0254, 1e-12);
  EXPECT_EQ(one.stored, "1 × 1 px/m");
  EXPECT_NEAR(resolution_from_memory(png_storing(1, 1, 1))->dpi_x, 0.0254, 1e-12);  // positive: the plain reader passes it on
  const StoredResolution zero = stored_resolution_from_memory(png_storing(0, 0, 1));
  EXPECT_EQ(zero.kind, StoredResolution::Kind::value);
  EXPECT_EQ(zero.dpi_x, 0.0);
  EXPECT_FALSE(resolution_from_memory(png_storing(0, 0, 1)).has_value());  // the old reader's contract: only positive values
  const StoredResolution aspect = stored_resolution_from_memory(png_storing(3, 2, 0));
  EXPECT_EQ(aspect.kind, StoredResolution::Kind::aspect_only);
  EXPECT_EQ(aspect.stored, "a pixel aspect ratio 3:2 (unit 0)");
  EXPECT_EQ(stored_resolution_from_memory(encoded(".png")).kind, StoredResolution::Kind::none);
}

// A density outside the resolutions a scan can have is a wrong scale, not a resolution: refused, naming
// what the file stores, unless --dpi gives the resolution; an aspect ratio alone is said to be one.
TEST(Resolution, LoadScanRefusesADensityOutsideTheScanRangeAndSaysWhatTheFileStores) {
  test::TempDir dir;
  const auto write = [&](const char* name, const std::vector<std::uint8_t>& bytes) {
    std::ofstream(dir / name, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return dir / name;
  };
  struct Case {
    const char* name;
    std::uint32_t ppm;
    const char* says;
  };
  for (const Case& c : {Case{"one.png", 1, "1 × 1 px/m"}, Case{"zero.png", 0, "0 × 0 px/m"},
                        Case{"huge.png", 4000000000U, "4000000000 × 4000000000 px/m"}, Case{"low.png", 393, "393 × 393 px/m"}}) {
    const auto path = write(c.name, png_storing(c.ppm, c.ppm, 1));
    try {
      (void)load_scan(path);
      ADD_FAILURE() << c.name << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.where().file, path.string());
      EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("--dpi"), std::string::npos) << e.what();
    }
    EXPECT_EQ(load_scan(path, 1200.0).dpi, 1200.0);  // the file's value is not used then
  }
  // 394 px/m is the rounding of 10 dpi, the range's lower end: accepted (with the low-resolution warning).
  const ScanImage edge = load_scan(write("edge.png", png_storing(394, 394, 1)));
  EXPECT_EQ(edge.dpi, 10.0);
  EXPECT_EQ(edge.warnings.size(), 1u);
  const ScanImage aspect = load_scan(write("aspect.png", png_storing(1, 1, 0)));
  EXPECT_EQ(aspect.dpi_source, "default");
  ASSERT_EQ(aspect.warnings.size(), 1u);
  EXPECT_NE(aspect.warnings[0].find("stores only a pixel aspect ratio 1:1"), std::string::npos) << aspect.warnings[0];
}

}  // namespace
}  // namespace stiffpath::vision
