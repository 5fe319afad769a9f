// NumPy ↔ OpenCV helpers of the Python vision module.
#include "images.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace stiffpath::python {

ImageArray image_view(const py::handle& value, const char* what, bool colour) {
  const char* expected = colour ? "a uint8 or uint16 array of shape (H, W) or (H, W, 3)" : "a uint8 or uint16 array of shape (H, W)";
  int depth = 0;
  py::array array;
  if (py::isinstance<py::array_t<std::uint8_t>>(value)) {
    array = py::array_t<std::uint8_t, py::array::c_style>::ensure(value);
    depth = CV_8U;
  } else if (py::isinstance<py::array_t<std::uint16_t>>(value)) {
    array = py::array_t<std::uint16_t, py::array::c_style>::ensure(value);
    depth = CV_16U;
  } else {
    std::string got = py::str(py::type::of(value).attr("__name__"));
    if (py::isinstance<py::array>(value)) got += " of dtype " + py::str(value.attr("dtype")).cast<std::string>();
    throw py::type_error(fmt::format("{}: expected {}, got {}", what, expected, got));
  }
  const bool three = array.ndim() == 3 && array.shape(2) == 3;
  if (!(array.ndim() == 2 || (colour && three))) {
    throw py::value_error(fmt::format("{}: expected {}, got shape {}{}", what, expected,
                                      py::str(array.attr("shape")).cast<std::string>(),
                                      !colour && three ? ": convert a colour image to grey first" : ""));
  }
  constexpr py::ssize_t most = std::numeric_limits<int>::max();
  if (array.shape(0) > most || array.shape(1) > most) throw py::value_error(fmt::format("{}: the image is too large", what));
  // The cv::Mat only borrows the pixels; the scan analysis reads them and does not write.
  cv::Mat mat(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)), CV_MAKETYPE(depth, three ? 3 : 1),
              const_cast<void*>(array.data()), static_cast<std::size_t>(array.strides(0)));
  return {std::move(array), mat};
}

py::array image_array(const cv::Size& size, int type, cv::Mat& view) {
  std::vector<py::ssize_t> shape{size.height, size.width};
  if (CV_MAT_CN(type) != 1) shape.push_back(CV_MAT_CN(type));
  py::array out = CV_MAT_DEPTH(type) == CV_16U ? py::array(py::dtype::of<std::uint16_t>(), shape)
                                               : py::array(py::dtype::of<std::uint8_t>(), shape);
  view = cv::Mat(size, type, out.mutable_data());
  return out;
}

std::string path_text(const py::handle& path) { return py::str(py::module_::import("os").attr("fspath")(path)); }

}  // namespace stiffpath::python
