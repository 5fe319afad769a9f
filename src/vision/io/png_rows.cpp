// A PNG written band by band with libpng (resolution in pHYs), so an image of any size passes through a few rows of memory.
#include <csetjmp>
#include <fmt/format.h>
#include <png.h>
#include <zlib.h>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/io/image_io.hpp"

namespace stiffpath::vision {

struct PngRowWriter::Impl {
  core::AtomicFile file;
  png_structp png = nullptr;
  png_infop info = nullptr;
  int width = 0, height = 0, type = 0, written = 0;
  std::string message;  // libpng's error, raised after its longjmp

  explicit Impl(const std::filesystem::path& path) : file(path) {}
  ~Impl() { png_destroy_write_struct(&png, &info); }
};

namespace {

void on_write(png_structp png, png_bytep data, png_size_t length) {
  auto* impl = static_cast<PngRowWriter::Impl*>(png_get_io_ptr(png));
  impl->file.stream().write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
  if (!impl->file.stream()) png_error(png, "write failed (disk full?)");
}

void on_flush(png_structp) {}

void on_error(png_structp png, png_const_charp message) {
  static_cast<PngRowWriter::Impl*>(png_get_error_ptr(png))->message = message;
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

// Runs one libpng step; a libpng error comes back through longjmp and is thrown as stiffpath::Error.
// The step holds no C++ object that needs destroying between setjmp and the libpng calls.
template <class Step>
void guarded(PngRowWriter::Impl& impl, const Step& step) {
  bool failed = false;
  if (setjmp(png_jmpbuf(impl.png)) != 0) {
    failed = true;
  } else {
    step();
  }
  if (failed) throw Error(SourceLocation{impl.file.path().string(), 0, 0}, "PNG encoding failed: " + impl.message);
}

}  // namespace

PngRowWriter::PngRowWriter(const std::filesystem::path& path, int width, int height, int type, double dpi)
    : impl_(std::make_unique<Impl>(path)) {
  const SourceLocation where{path.string(), 0, 0};
  const int depth = CV_MAT_DEPTH(type), channels = CV_MAT_CN(type);
  if (width < 1 || height < 1) throw Error(where, fmt::format("a PNG needs at least one pixel, got {} × {}", width, height));
  if ((depth != CV_8U && depth != CV_16U) || (channels != 1 && channels != 3)) {
    throw Error(where, "a PNG is written from 8- or 16-bit grey or BGR rows");
  }
  if (!(dpi > 0.0) || !std::isfinite(dpi) || dpi > 65535.0) throw Error(where, fmt::format("resolution must be in (0, 65535] dpi, got {}", dpi));
  Impl& impl = *impl_;
  impl.width = width, impl.height = height, impl.type = type;
  impl.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &impl, on_error, on_warning);
  if (impl.png == nullptr) throw Error(where, "cannot start a PNG encoder");
  impl.info = png_create_info_struct(impl.png);
  if (impl.info == nullptr) throw Error(where, "cannot start a PNG encoder");
  const auto ppm = static_cast<png_uint_32>(std::llround(dpi / 0.0254));
  guarded(impl, [&] {
    png_set_write_fn(impl.png, &impl, on_write, on_flush);
    png_set_IHDR(impl.png, impl.info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), depth == CV_8U ? 8 : 16,
                 channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_pHYs(impl.png, impl.info, ppm, ppm, PNG_RESOLUTION_METER);
    // As OpenCV writes PNGs: the Sub filter on every row, run-length deflate at level 1 (fast; a scan's
    // noise compresses little anyway; trying every filter per row doubles the time for 10 % of size).
    png_set_filter(impl.png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_set_compression_strategy(impl.png, Z_RLE);
    png_set_compression_level(impl.png, 1);
    png_write_info(impl.png, impl.info);
    if (channels == 3) png_set_bgr(impl.png);
    if (depth == CV_16U) png_set_swap(impl.png);  // rows in memory are little-endian on our targets
  });
}

PngRowWriter::~PngRowWriter() = default;

void PngRowWriter::write(const cv::Mat& rows) {
  Impl& impl = *impl_;
  const SourceLocation where{impl.file.path().string(), 0, 0};
  if (rows.type() != impl.type || rows.cols != impl.width || impl.written + rows.rows > impl.height) {
    throw Error(where, fmt::format("PNG rows do not match the image ({} × {}, {} rows written, {} more given)", impl.width,
                                   impl.height, impl.written, rows.rows));
  }
  for (int y = 0; y < rows.rows; ++y) {
    png_bytep row = const_cast<png_bytep>(rows.ptr<png_byte>(y));
    guarded(impl, [&] { png_write_row(impl.png, row); });
  }
  impl.written += rows.rows;
}

void PngRowWriter::commit() {
  Impl& impl = *impl_;
  if (impl.written != impl.height) {
    throw Error(SourceLocation{impl.file.path().string(), 0, 0},
                fmt::format("PNG incomplete: {} of {} rows written", impl.written, impl.height));
  }
  guarded(impl, [&] { png_write_end(impl.png, nullptr); });
  impl.file.commit();
}

}  // namespace stiffpath::vision
