// Text for the overlay: OpenCV's Hershey font at a given height, with µ and ² drawn by hand, wrapping; not installed.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace stiffpath::vision::detail {

//! Text of a given cap height (px) in the Hershey simplex font; "µ", "²" and "±" (UTF-8), which the
//! font lacks, are drawn as a u with a descender, a raised small 2 and an underlined plus.
class OverlayFont {
 public:
  explicit OverlayFont(int height_px);
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] int thickness() const noexcept { return thickness_; }
  //! Width of the text (px).
  [[nodiscard]] int width(const std::string& text) const;
  //! Draws with the baseline's left end at `origin`; returns the box the text covers (ascent to descent).
  cv::Rect draw(cv::Mat& image, const std::string& text, cv::Point origin, const cv::Scalar& colour) const;
  //! Splits text at ", " into lines no wider than max_width (a piece wider than that gets a line of its own).
  [[nodiscard]] std::vector<std::string> wrap(const std::string& text, int max_width) const;

 private:
  int height_, thickness_;
  double scale_;
};

}  // namespace stiffpath::vision::detail
