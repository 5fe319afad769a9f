// The Python module `stiffpath.vision` (built as _stiffpath_vision): scans, the one part of the library that loads OpenCV.
#include <pybind11/pybind11.h>

#include "parts.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_stiffpath_vision, m) {
  m.doc() =
      "stiffpath.vision: measuring laser-marked paths on scans (thesis §4.6) and drawing synthetic scans, as\n"
      "`stiffpath scan` and `stiffpath render-scan` do. Reached as stiffpath.vision, which imports it (and OpenCV)\n"
      "on first use; `import stiffpath` alone loads neither.\n\n"
      "SI units throughout, in the image frame: x to the right, y down, from the top-left corner of the top-left\n"
      "pixel, in m. Bad input raises stiffpath.Error (a ValueError with file, line and column attributes).";
  // The core module registers the types this one returns (PathMetrics, SideMetrics, CornerReport) and translates
  // stiffpath::Error into stiffpath.Error for every module of this build (pybind11's translators are shared).
  m.attr("Error") = py::module_::import("stiffpath").attr("Error");
  stiffpath::python::add_scan(m);
  stiffpath::python::add_render(m);
  stiffpath::python::add_calibrate(m);
}
