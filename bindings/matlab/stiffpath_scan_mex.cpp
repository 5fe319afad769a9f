// The MATLAB/Octave gateway `stiffpath_scan(image, options)` (called by stiffpath('scan', …)): a scanned mark
// measured as `stiffpath scan --json`. A gateway of its own so that only a scan loads OpenCV.
#include <mex.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "mex_args.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace {

using namespace stiffpath;
using namespace stiffpath::mex;

// A uint8 or uint16 grey matrix (MATLAB: rows down, column-major) as a cv::Mat (row-major).
cv::Mat grey_of(const mxArray* a) {
  const bool u8 = mxIsUint8(a), u16 = mxIsUint16(a);
  if (!(u8 || u16) || mxGetNumberOfDimensions(a) != 2 || mxIsComplex(a)) {
    throw UsageError("image must be an image file name or a uint8/uint16 grey matrix");
  }
  const int rows = static_cast<int>(mxGetM(a)), cols = static_cast<int>(mxGetN(a));
  if (rows < 2 || cols < 2) throw Error(fmt::format("image: a {}×{} matrix holds no mark", rows, cols));
  cv::Mat m(rows, cols, u8 ? CV_8U : CV_16U);
  for (int c = 0; c < cols; ++c) {
    for (int r = 0; r < rows; ++r) {
      const std::size_t k = static_cast<std::size_t>(c) * rows + r;
      if (u8) {
        m.at<std::uint8_t>(r, c) = static_cast<const std::uint8_t*>(mxGetData(a))[k];
      } else {
        m.at<std::uint16_t>(r, c) = static_cast<const std::uint16_t*>(mxGetData(a))[k];
      }
    }
  }
  return m;
}

void scan(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 1, 2, "m = stiffpath('scan', image [, options])  % options: dpi, shape, spline_cutoff_m, corner_trim_m, roi_px");
  Options o(nrhs == 2 ? prhs[1] : nullptr);
  const auto dpi = o.number("dpi", 50.0, 20000.0, "dpi");
  vision::ScanOptions options;
  if (const auto shape = o.text("shape")) {
    const vision::ScanShape parsed = vision::parse_scan_shape(*shape, "options.shape");
    options.sides = parsed.sides;
    options.metrics.closure = parsed.closure;
  }
  options.metrics.smoothing_cutoff_m = o.number("spline_cutoff_m", 1e-5, 1.0, "m").value_or(options.metrics.smoothing_cutoff_m);
  options.metrics.corner_trim_m = o.number("corner_trim_m", 0.0, 1.0, "m").value_or(options.metrics.corner_trim_m);
  if (const mxArray* roi = o.raw("roi_px")) {
    const Matrix r = matrix_arg(roi, "options.roi_px", 4, 4);
    if (r.rows != 1 || r(0, 0) < 0 || r(0, 1) < 0 || r(0, 2) <= 0 || r(0, 3) <= 0) {
      throw Error("options.roi_px: expected [x y width height] with x, y >= 0 and width, height > 0");
    }
    options.roi_px = cv::Rect(static_cast<int>(r(0, 0)), static_cast<int>(r(0, 1)), static_cast<int>(r(0, 2)),
                              static_cast<int>(r(0, 3)));
  }
  o.finish();
  vision::ScanImage image;
  if (mxIsChar(prhs[0])) {
    options.label = text_arg(prhs[0], "image");
    image = vision::load_scan(options.label, dpi);
  } else {
    options.label = "<matrix>";
    if (!dpi) throw Error("<matrix>: a matrix holds no resolution: give options.dpi");
    image.grey = grey_of(prhs[0]);
    image.dpi = *dpi;
    image.dpi_source = "options.dpi";
  }
  vision::ScanResult result = vision::analyse_scan(image.grey, image.dpi, options);
  result.warnings.insert(result.warnings.begin(), image.warnings.begin(), image.warnings.end());
  nlohmann::json out = vision::to_json(result);
  out["shape"] = vision::shape_name(result);
  out["image"] = options.label;
  out["dpi_source"] = image.dpi_source;
  std::vector<Vec2> points;
  for (const auto& side : result.sides) {
    for (const auto& p : side.centres) points.emplace_back(p.x(), p.y());
  }
  mxArray* s = from_json(out);
  mxAddField(s, "points_m");
  mxSetField(s, 0, "points_m", pairs(points));
  plhs[0] = s;
}

std::string dispatch(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[], std::string& id) {
  try {
    scan(nlhs, plhs, nrhs, prhs);
    return {};
  } catch (const stiffpath::Error& e) {
    id = "stiffpath:badInput";
    return e.what();
  } catch (const UsageError& e) {
    id = "stiffpath:usage";
    return e.what();
  } catch (const std::exception& e) {
    id = "stiffpath:internal";
    return std::string("internal error: ") + e.what();
  }
}

}  // namespace

void mexFunction(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  static char message[4096];
  static char id[64];
  {
    std::string error_id;
    const std::string error = dispatch(nlhs, plhs, nrhs, prhs, error_id);
    if (error.empty()) return;
    std::snprintf(message, sizeof message, "%s", error.c_str());
    std::snprintf(id, sizeof id, "%s", error_id.c_str());
  }
  mexErrMsgIdAndTxt(id, "%s", message);
}
