// The parts of the Python vision module, one source file each.
#pragma once

#include <pybind11/pybind11.h>

namespace stiffpath::python {

namespace py = pybind11;

void add_scan(py::module_& m);    //!< scan, scan_plate, ScanResult, ScanSide, PlateResult, PlateMark
void add_render(py::module_& m);  //!< render_scan, RenderedScan, save_image
void add_calibrate(py::module_& m);  //!< calibrate_fit: `stiffpath calibrate fit`

}  // namespace stiffpath::python
