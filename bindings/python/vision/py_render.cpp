// Python: synthetic scans of a marked path with their ground truth, as `stiffpath render-scan` draws them, and image files.
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "../arrays.hpp"
#include "images.hpp"
#include "parts.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/vision/render/plate.hpp"
#include "stiffpath/vision/render/render.hpp"

namespace stiffpath::python {

namespace {

// A rendered scan as Python keeps it: the image as a NumPy array and what is known about it.
struct PyRendered {
  py::array image;
  double dpi = 0;
  double mark_width_m = 0;
  std::vector<std::vector<evaluation::Point2>> sides;
  bool closed = false;
  evaluation::PathMetrics truth;
};

// The ranges `stiffpath render-scan` accepts for the path's size, so that no call samples an absurd path (the
// path is sampled every 20 µm, and every λ/100 with a wiggle, before the image's size is checked).
void check_range(double value, double lo, double hi, const char* name) {
  if (!(value >= lo && value <= hi)) throw py::value_error(fmt::format("{}: expected a value in [{}, {}], got {}", name, lo, hi, value));
}

void save(const std::string& path, const py::handle& image, double dpi) {
  const ImageArray pixels = image_view(image, "image", true);
  py::gil_scoped_release unlocked;
  vision::write_image(path, pixels.mat, dpi);
}

PyRendered render_scan(const std::string& shape, double length_m, double side_m, const std::optional<py::object>& vertices_m,
                       const std::optional<std::string>& path_csv, int sides, double angle_rad, double width_m,
                       double margin_m, double wiggle_m, double wiggle_wavelength_m, double wiggle_decay_m,
                       double corner_trim_m, double dpi, double blur_px, double noise, double texture, double shading,
                       int specks, int bit_depth, bool colour, std::uint64_t seed) {
  vision::RenderOptions options;
  options.dpi = dpi;
  options.mark_width_m = width_m;
  options.rotation_rad = angle_rad;
  options.margin_m = margin_m;
  options.blur_px = blur_px;
  options.noise = noise;
  options.texture = texture;
  options.shading = shading;
  options.specks = specks;
  options.bit_depth = bit_depth;
  options.colour = colour;
  options.seed = seed;
  if (!(corner_trim_m >= 0.0) || !std::isfinite(corner_trim_m)) {
    throw py::value_error(fmt::format("corner_trim_m: expected a length >= 0 in m, got {}", corner_trim_m));
  }
  options.truth_options.corner_trim_m = corner_trim_m;

  std::vector<std::vector<evaluation::Point2>> path;
  bool closed = false;
  if (path_csv) {
    check_range(sides, 1, 64, "sides");
    py::gil_scoped_release unlocked;
    auto mark = vision::load_mark_csv(*path_csv, sides);
    path = std::move(mark.sides);
    closed = mark.closed;
  } else {
    vision::PathShape nominal;
    if (shape == "line") {
      check_range(length_m, 1e-5, 2.0, "length_m");
      nominal = vision::line_shape(length_m);
    } else if (shape == "triangle") {
      check_range(side_m, 1e-5, 2.0, "side_m");
      nominal = vision::triangle_shape(side_m);
    } else if (shape == "polyline") {
      if (!vertices_m) throw py::value_error("shape='polyline' needs vertices_m, an (N, 2) array in m");
      const auto v = pairs(*vertices_m, "vertices_m");
      if (v.ndim() != 2 || v.shape(0) < 2) throw py::value_error("vertices_m: expected an (N, 2) array with N >= 2");
      for (py::ssize_t i = 0; i < v.shape(0); ++i) nominal.vertices.emplace_back(v.at(i, 0), v.at(i, 1));
      (void)vision::rendered_size({nominal.vertices}, options);  // refuses a path whose image would be too large
    } else {
      throw py::value_error(fmt::format("shape: expected 'line', 'triangle' or 'polyline', got '{}'", shape));
    }
    check_range(wiggle_m, 0.0, 0.1, "wiggle_m");
    check_range(wiggle_wavelength_m, 1e-6, 10.0, "wiggle_wavelength_m");
    check_range(wiggle_decay_m, 1e-6, 1000.0, "wiggle_decay_m");
    closed = nominal.closed;
    py::gil_scoped_release unlocked;
    path = vision::sample_shape(nominal, {wiggle_m, wiggle_wavelength_m, wiggle_decay_m});
  }

  const cv::Size size = vision::rendered_size(path, options);
  cv::Mat view;
  PyRendered out;
  out.image = image_array(size, CV_MAKETYPE(bit_depth == 16 ? CV_16U : CV_8U, colour ? 3 : 1), view);
  py::gil_scoped_release unlocked;
  // Straight into the array, band by band: the image is never held twice.
  vision::RenderedScan scan = vision::render_scan(path, closed, options, [&view](int first_row, const cv::Mat& rows) {
    rows.copyTo(view.rowRange(first_row, first_row + rows.rows));
  });
  out.dpi = scan.dpi;
  out.mark_width_m = scan.mark_width_m;
  out.sides = std::move(scan.sides);
  out.closed = scan.closed;
  out.truth = std::move(scan.truth);
  return out;
}

}  // namespace

void add_render(py::module_& m) {
  py::class_<PyRendered>(m, "RenderedScan", "A synthetic scan and its ground truth (SI units, image frame: x right, y down).")
      .def_readonly("image", &PyRendered::image,
                    "the pixels: (H, W) grey or (H, W, 3) BGR, uint8 or uint16, row 0 at the top")
      .def_readonly("dpi", &PyRendered::dpi, "resolution (dots per inch)")
      .def_readonly("mark_width_m", &PyRendered::mark_width_m, "width of the mark = laser spot diameter (m)")
      .def_property_readonly(
          "sides_m",
          [](const PyRendered& r) {
            py::list out;
            for (const auto& side : r.sides) out.append(points_array(side));
            return out;
          },
          "the marked centre path per side, (N, 2) arrays in m in the image frame; consecutive sides share their corner")
      .def_readonly("closed", &PyRendered::closed)
      .def_readonly("truth", &PyRendered::truth, "stiffpath.PathMetrics of the exact centre path: what a scan should measure")
      .def(
          "save", [](const PyRendered& r, const py::object& path) { save(path_text(path), r.image, r.dpi); },
          py::arg("path"), "Writes the image as save_image(path, image, dpi) does.");

  m.def("render_scan", &render_scan, py::kw_only(), py::arg("shape") = "line", py::arg("length_m") = 0.1,
        py::arg("side_m") = 0.04, py::arg("vertices_m") = py::none(), py::arg("path_csv") = py::none(), py::arg("sides") = 1,
        py::arg("angle_rad") = 0.0, py::arg("width_m") = vision::RenderOptions{}.mark_width_m,
        py::arg("margin_m") = vision::RenderOptions{}.margin_m, py::arg("wiggle_m") = vision::Wiggle{}.amplitude_m,
        py::arg("wiggle_wavelength_m") = vision::Wiggle{}.wavelength_m,
        py::arg("wiggle_decay_m") = vision::Wiggle{}.decay_length_m,
        py::arg("corner_trim_m") = evaluation::PathMetricsOptions{}.corner_trim_m,
        py::arg("dpi") = vision::RenderOptions{}.dpi, py::arg("blur_px") = vision::RenderOptions{}.blur_px,
        py::arg("noise") = vision::RenderOptions{}.noise, py::arg("texture") = vision::RenderOptions{}.texture,
        py::arg("shading") = vision::RenderOptions{}.shading, py::arg("specks") = vision::RenderOptions{}.specks,
        py::arg("bit_depth") = vision::RenderOptions{}.bit_depth, py::arg("colour") = vision::RenderOptions{}.colour,
        py::arg("seed") = vision::RenderOptions{}.seed,
        "Draws a synthetic scan of a laser-marked path, as `stiffpath render-scan` with the same defaults (a 1200 dpi\n"
        "office scan of a 0.2 mm mark on coated chipboard), and returns it with its ground truth (RenderedScan).\n\n"
        "The path: shape 'line' (length_m along x), 'triangle' (equilateral, side_m) or 'polyline' (vertices_m, an\n"
        "(N, 2) array in m, y down), with a decaying vibration across it of amplitude wiggle_m (m), wavelength\n"
        "wiggle_wavelength_m and decay length wiggle_decay_m along the path; or path_csv, a CSV file with x_mm, y_mm\n"
        "columns in marking order cut into `sides` sides (a simulated mark). angle_rad turns it (clockwise on the\n"
        "image, y down); width_m is the mark's width, margin_m the paper around it (m).\n"
        "The scanner: dpi, blur_px (σ of the blur, px), noise and texture (σ, fractions of full scale and of the\n"
        "paper's brightness), shading (illumination falloff, fraction), specks (dust), bit_depth 8 or 16, colour\n"
        "(BGR), seed. corner_trim_m: the truth's corner trim (m), as scan()'s. At most 200 Mpx. Releases the GIL.");

  m.def(
      "save_image", [](const py::object& path, const py::handle& image, double dpi) { save(path_text(path), image, dpi); },
      py::arg("path"), py::arg("image"), py::arg("dpi"),
      "Writes an image (uint8 or uint16, (H, W) grey or (H, W, 3) BGR) to a .png, .tif/.tiff or .jpg/.jpeg file with\n"
      "`dpi` (dots per inch) in its metadata, so that scan() reads the resolution back. The file appears only when\n"
      "it is complete. Raises stiffpath.Error for another extension.");
}

}  // namespace stiffpath::python
