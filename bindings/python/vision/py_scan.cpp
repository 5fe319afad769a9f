// Python: measuring the marked path on a scan (a file or an array) or every mark of a plate, as `stiffpath scan` does.
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "../arrays.hpp"
#include "images.hpp"
#include "parts.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::python {

namespace {

// A scan ready for the analysis: read from a file (its resolution from the metadata unless dpi is given) or the
// caller's array (then dpi is required), which `pixels` keeps alive.
struct Source {
  ImageArray pixels;
  vision::ScanImage scan;
  std::string label;  // the file, or "<array>", as errors and to_dict() name it
};

Source read_source(const py::handle& image, std::optional<double> dpi) {
  Source source;
  if (py::isinstance<py::str>(image) || py::hasattr(image, "__fspath__")) {
    source.label = path_text(image);
    {
      py::gil_scoped_release unlocked;
      source.scan = vision::load_scan(source.label, dpi);
    }
    return source;
  }
  source.pixels = image_view(image, "image", false);
  source.label = "<array>";
  if (!dpi) throw Error({source.label, 0, 0}, "an array holds no resolution: give dpi");
  source.scan.grey = source.pixels.mat;
  source.scan.dpi = *dpi;
  source.scan.dpi_source = "dpi argument";
  return source;
}

vision::ScanOptions scan_options(const std::optional<std::string>& shape, int sides_by_default, double spline_cutoff_m,
                                 double corner_trim_m, const std::optional<std::array<int, 4>>& roi_px,
                                 const std::string& label) {
  vision::ScanOptions options;
  options.sides = sides_by_default;
  if (shape) {
    const vision::ScanShape parsed = vision::parse_scan_shape(*shape, "shape");
    options.sides = parsed.sides;
    options.metrics.closure = parsed.closure;
  }
  options.metrics.smoothing_cutoff_m = spline_cutoff_m;
  options.metrics.corner_trim_m = corner_trim_m;
  options.label = label;
  if (roi_px) {
    const auto& r = *roi_px;
    if (r[0] < 0 || r[1] < 0 || r[2] <= 0 || r[3] <= 0) {
      throw py::value_error(fmt::format("roi_px: expected (x, y, width, height) with x, y >= 0 and width, height > 0, got "
                                        "({}, {}, {}, {})", r[0], r[1], r[2], r[3]));
    }
    options.roi_px = cv::Rect(r[0], r[1], r[2], r[3]);
  }
  return options;
}

// One measured path as Python sees it: the library's result and where the image came from.
struct PyScan {
  vision::ScanResult result;
  std::string image;
  std::string dpi_source;
  cv::Rect roi_px;
};

// The document `stiffpath scan --json` prints.
nlohmann::json scan_json(const PyScan& s) {
  nlohmann::json out = vision::to_json(s.result);
  out["shape"] = vision::shape_name(s.result);
  out["image"] = s.image;
  out["dpi_source"] = s.dpi_source;
  if (!s.roi_px.empty()) {
    const double mm = 25.4 / s.result.dpi;
    out["roi_mm"] = {s.roi_px.x * mm, s.roi_px.y * mm, s.roi_px.width * mm, s.roi_px.height * mm};
  }
  return out;
}

py::object to_python(const nlohmann::json& document) { return py::module_::import("json").attr("loads")(document.dump()); }

py::array_t<double> all_centres(const vision::ScanResult& r) {
  std::vector<Vec2> points;
  for (const auto& side : r.sides) points.insert(points.end(), side.centres.begin(), side.centres.end());
  return points_array(points);
}

// A plate as Python sees it: the library's result, where the image came from and what reading it warned about.
struct PyPlate {
  vision::PlateResult plate;
  std::string image;
  std::string dpi_source;
  std::vector<std::string> warnings;
  cv::Rect roi_px;
};

// One mark of a plate; `result` only when it was measured.
struct PyPlateMark {
  int index = 0;
  std::array<double, 4> box_m{};
  bool measured = false;
  std::string reason;
  std::optional<PyScan> result;
};

std::array<double, 4> box(const cv::Rect2d& b) { return {b.x, b.y, b.width, b.height}; }

PyScan scan(const py::object& image, std::optional<double> dpi, const std::optional<std::string>& shape,
            double spline_cutoff_m, double corner_trim_m, const std::optional<std::array<int, 4>>& roi_px) {
  Source source = read_source(image, dpi);
  const vision::ScanOptions options = scan_options(shape, 1, spline_cutoff_m, corner_trim_m, roi_px, source.label);
  PyScan out{{}, source.label, source.scan.dpi_source, options.roi_px};
  py::gil_scoped_release unlocked;
  out.result = vision::analyse_scan(source.scan.grey, source.scan.dpi, options);
  out.result.warnings.insert(out.result.warnings.begin(), source.scan.warnings.begin(), source.scan.warnings.end());
  return out;
}

PyPlate scan_plate(const py::object& image, std::optional<double> dpi, const std::optional<std::string>& shape,
                   double min_mark_m, double spline_cutoff_m, double corner_trim_m,
                   const std::optional<std::array<int, 4>>& roi_px) {
  Source source = read_source(image, dpi);
  vision::ScanOptions options = scan_options(shape, 0, spline_cutoff_m, corner_trim_m, roi_px, source.label);
  if (!(min_mark_m > 0.0) || !std::isfinite(min_mark_m)) {
    throw py::value_error(fmt::format("min_mark_m: expected a positive size in m, got {}", min_mark_m));
  }
  options.min_plate_mark_m = min_mark_m;
  PyPlate out{{}, source.label, source.scan.dpi_source, source.scan.warnings, options.roi_px};
  py::gil_scoped_release unlocked;
  out.plate = vision::analyse_plate(source.scan.grey, source.scan.dpi, options);
  return out;
}

}  // namespace

void add_scan(py::module_& m) {
  py::class_<vision::ScanSide>(m, "ScanSide", "What the scan says about one straight side beyond its metrics (SI).")
      .def_property_readonly("centres_m", [](const vision::ScanSide& s) { return points_array(s.centres); },
                             "sub-pixel centre-line points (N, 2) in m, image frame (x right, y down from the top-left\n"
                             "corner of the top-left pixel), the round ends' cap centres included")
      .def_readonly("width_m", &vision::ScanSide::width_m, "median width of the mark's cross-sections (m)")
      .def_readonly("sections", &vision::ScanSide::sections, "cross-sections measured")
      .def_readonly("rejected_sections", &vision::ScanSide::rejected_sections, "left out as outliers (dust, gaps)");

  py::class_<PyScan>(m, "ScanResult", "A marked path measured on a scan (thesis §4.6), SI units, image frame.")
      .def_property_readonly("metrics", [](const PyScan& s) { return s.result.metrics; },
                             "stiffpath.PathMetrics: length, deviation area, max deviation, straightness, sides, corners")
      .def_property_readonly("points_m", [](const PyScan& s) { return all_centres(s.result); },
                             "the centre-line points of every side, one side after the other, (N, 2) in m")
      .def_property_readonly("sides", [](const PyScan& s) { return s.result.sides; }, "ScanSide per side, as metrics.sides")
      .def_property_readonly("shape", [](const PyScan& s) { return vision::shape_name(s.result); },
                             "'line', 'triangle' or 'polyline:N': what was measured")
      .def_property_readonly("width_m", [](const PyScan& s) { return s.result.width_m; }, "median mark width over all sides (m)")
      .def_property_readonly("length_uncertainty_m", [](const PyScan& s) { return s.result.length_uncertainty_m; },
                             "bound on the length's error from free ends that are not round spot ends (m); 0 when all are")
      .def_property_readonly("mark_darkness", [](const PyScan& s) { return s.result.mark_darkness; },
                             "1 − mark/paper brightness of the fully marked core")
      .def_property_readonly("paper_noise", [](const PyScan& s) { return s.result.paper_noise; },
                             "robust σ of the paper's relative brightness")
      .def_property_readonly("specks_ignored", [](const PyScan& s) { return s.result.specks_ignored; })
      .def_property_readonly("dpi", [](const PyScan& s) { return s.result.dpi; }, "resolution used (dots per inch)")
      .def_property_readonly("dpi_source", [](const PyScan& s) { return s.dpi_source; },
                             "'PNG pHYs', 'TIFF XResolution', 'JPEG JFIF', 'JPEG Exif', '--dpi' (given), 'dpi argument'\n"
                             "(an array) or 'default' (1200 assumed, with a warning)")
      .def_property_readonly("image", [](const PyScan& s) { return s.image; }, "the file, or '<array>'")
      .def_property_readonly("image_size_px", [](const PyScan& s) { return std::pair(s.result.width_px, s.result.height_px); },
                             "(width, height) of the whole image in px")
      .def_property_readonly("warnings", [](const PyScan& s) { return s.result.warnings; },
                             "conditions that may bias the numbers (an assumed resolution, a cut end, …)")
      .def("to_dict", [](const PyScan& s) { return to_python(scan_json(s)); },
           "The document `stiffpath scan --json` prints for this scan (mm, mm², units in the keys).");

  m.def("scan", &scan, py::arg("image"), py::kw_only(), py::arg("dpi") = py::none(), py::arg("shape") = py::none(),
        py::arg("spline_cutoff_m") = evaluation::PathMetricsOptions{}.smoothing_cutoff_m,
        py::arg("corner_trim_m") = evaluation::PathMetricsOptions{}.corner_trim_m, py::arg("roi_px") = py::none(),
        "Measures the one laser-marked path on a scan, as `stiffpath scan` (thesis §4.6): segmentation, sub-pixel\n"
        "centre line, line and spline fits, px → m, the §4.7 metrics.\n\n"
        "image: a file name (PNG, TIFF or JPEG; grey or colour; 8 or 16 bit) or a grey image as a uint8 or uint16\n"
        "  NumPy array of shape (H, W), row 0 at the top.\n"
        "dpi: resolution in dots per inch; for a file it overrides the metadata (default: the metadata, else 1200\n"
        "  with a warning); required for an array.\n"
        "shape: 'line' (default), 'triangle', 'polyline:N' (N straight sides, 1..64) or 'any'.\n"
        "spline_cutoff_m: cutoff wavelength of the smoothing spline (m); corner_trim_m: part of each side next to a\n"
        "  corner left out of the metrics (m); as --spline-cutoff-mm and --corner-trim-mm, 1 mm each by default.\n"
        "roi_px: measure only the region (x, y, width, height) in px of the image; positions stay in the image frame.\n"
        "Returns a ScanResult. Raises stiffpath.Error naming the file for a missing or unreadable image, no mark, two\n"
        "marks or a mark that does not split into the sides asked for. Releases the GIL.");

  py::class_<PyPlateMark>(m, "PlateMark", "One dark feature of a plate at least min_mark_m across and what became of it.")
      .def_readonly("index", &PyPlateMark::index, "1-based, in reading order (top edges)")
      .def_readonly("box_m", &PyPlateMark::box_m, "bounding box (x, y, width, height) in m, image frame")
      .def_readonly("measured", &PyPlateMark::measured)
      .def_readonly("reason", &PyPlateMark::reason, "why it was not measured ('' when it was)")
      .def_readonly("result", &PyPlateMark::result, "its ScanResult, None when it was not measured");

  py::class_<PyPlate>(m, "PlateResult", "Every mark on a scan of a plate (SI units, image frame).")
      .def_property_readonly(
          "marks",
          [](const PyPlate& p) {
            std::vector<PyPlateMark> marks;
            for (const auto& mark : p.plate.marks) {
              PyPlateMark out{mark.index, box(mark.box_m), mark.measured, mark.reason, std::nullopt};
              if (mark.measured) out.result = PyScan{mark.result, p.image, p.dpi_source, {}};
              marks.push_back(std::move(out));
            }
            return marks;
          },
          "PlateMark per mark, in reading order")
      .def_property_readonly(
          "labels",
          [](const PyPlate& p) {
            std::vector<std::pair<std::array<double, 4>, int>> labels;
            for (const auto& l : p.plate.labels) labels.emplace_back(box(l.box_m), l.features);
            return labels;
          },
          "label areas (smaller features grouped, not measured): ((x, y, width, height) in m, features)")
      .def_property_readonly("specks_ignored", [](const PyPlate& p) { return p.plate.specks_ignored; })
      .def_property_readonly("dpi", [](const PyPlate& p) { return p.plate.dpi; })
      .def_property_readonly("dpi_source", [](const PyPlate& p) { return p.dpi_source; })
      .def_property_readonly("image", [](const PyPlate& p) { return p.image; })
      .def_property_readonly("image_size_px", [](const PyPlate& p) { return std::pair(p.plate.width_px, p.plate.height_px); })
      .def_property_readonly("warnings", [](const PyPlate& p) { return p.warnings; }, "what reading the image warned about")
      .def(
          "to_dict",
          [](const PyPlate& p) {
            nlohmann::json out = vision::to_json(p.plate);
            out["warnings"] = p.warnings;
            out["image"] = p.image;
            out["dpi_source"] = p.dpi_source;
            if (!p.roi_px.empty()) {
              const double mm = 25.4 / p.plate.dpi;
              out["roi_mm"] = {p.roi_px.x * mm, p.roi_px.y * mm, p.roi_px.width * mm, p.roi_px.height * mm};
            }
            return to_python(out);
          },
          "The document `stiffpath scan --all-marks --json` prints (mm, units in the keys).");

  m.def("scan_plate", &scan_plate, py::arg("image"), py::kw_only(), py::arg("dpi") = py::none(),
        py::arg("shape") = py::none(), py::arg("min_mark_m") = vision::ScanOptions{}.min_plate_mark_m,
        py::arg("spline_cutoff_m") = evaluation::PathMetricsOptions{}.smoothing_cutoff_m,
        py::arg("corner_trim_m") = evaluation::PathMetricsOptions{}.corner_trim_m, py::arg("roi_px") = py::none(),
        "Measures every mark on a scan of a plate, as `stiffpath scan --all-marks`: each dark feature at least\n"
        "min_mark_m (m) across is measured as `shape` says (default 'any': its shape is found); smaller ones are\n"
        "grouped into label areas. The other arguments as for scan(). Returns a PlateResult; raises stiffpath.Error\n"
        "only for a bad image or options. Releases the GIL.");
}

}  // namespace stiffpath::python
