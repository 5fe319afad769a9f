// NumPy ↔ OpenCV helpers of the Python vision module: scans in, rendered images out, without copies where possible.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <opencv2/core.hpp>

#include <string>

namespace stiffpath::python {

namespace py = pybind11;

//! An image given as a NumPy array, seen by OpenCV without a copy: `array` keeps the pixels alive while
//! `mat` (CV_8U or CV_16U, one or three channels) is used, also with the GIL released.
struct ImageArray {
  py::array array;
  cv::Mat mat;
};

//! Views a uint8 or uint16 array of shape (H, W) — or (H, W, 3), BGR, when `colour` is allowed — as a
//! cv::Mat (after a C-contiguous copy if it is not one). TypeError naming `what` for another dtype or
//! type, ValueError for another shape.
ImageArray image_view(const py::handle& value, const char* what, bool colour);

//! A new C-contiguous array for an image of `size` and OpenCV `type` (CV_8U/CV_16U, one or three channels):
//! (H, W) or (H, W, 3), uint8 or uint16. `view` receives a cv::Mat over its pixels.
py::array image_array(const cv::Size& size, int type, cv::Mat& view);

//! A file name given as str or os.PathLike, as text (os.fspath).
std::string path_text(const py::handle& path);

}  // namespace stiffpath::python
