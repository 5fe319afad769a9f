// Overlay text: Hershey simplex at a given height, hand-drawn µ and ², widths and wrapping at commas.
#include "overlay_text.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace stiffpath::vision::detail {

namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const std::string kMicro = "\xC2\xB5", kSquared = "\xC2\xB2", kPlusMinus = "\xC2\xB1";

// The text cut into plain runs and the two special characters.
std::vector<std::string> pieces(const std::string& text) {
  std::vector<std::string> out{""};
  for (std::size_t i = 0; i < text.size();) {
    if (text.compare(i, 2, kMicro) == 0 || text.compare(i, 2, kSquared) == 0 || text.compare(i, 2, kPlusMinus) == 0) {
      out.push_back(text.substr(i, 2));
      out.emplace_back();
      i += 2;
    } else {
      out.back() += text[i++];
    }
  }
  return out;
}

}  // namespace

OverlayFont::OverlayFont(int height_px)
    : height_(std::max(8, height_px)), thickness_(std::max(1, static_cast<int>(std::lround(height_ / 11.0)))),
      scale_(cv::getFontScaleFromHeight(kFont, height_, thickness_)) {}

int OverlayFont::width(const std::string& text) const {
  int w = 0, base = 0;
  for (const auto& p : pieces(text)) {
    if (p == kMicro || p == kPlusMinus) {
      w += cv::getTextSize(p == kMicro ? "u" : "+", kFont, scale_, thickness_, &base).width;
    } else if (p == kSquared) {
      w += cv::getTextSize("2", kFont, 0.6 * scale_, thickness_, &base).width;
    } else if (!p.empty()) {
      w += cv::getTextSize(p, kFont, scale_, thickness_, &base).width;
    }
  }
  return w;
}

cv::Rect OverlayFont::draw(cv::Mat& image, const std::string& text, cv::Point origin, const cv::Scalar& colour) const {
  int x = origin.x, base = 0;
  for (const auto& p : pieces(text)) {
    if (p == kMicro) {
      const cv::Size s = cv::getTextSize("u", kFont, scale_, thickness_, &base);
      cv::putText(image, "u", {x, origin.y}, kFont, scale_, colour, thickness_, cv::LINE_AA);
      const int stem = x + thickness_ + s.width / 8;  // the u's left stem, carried below the baseline
      cv::line(image, {stem, origin.y - s.height / 2}, {stem, origin.y + height_ / 3}, colour, thickness_, cv::LINE_AA);
      x += s.width;
    } else if (p == kPlusMinus) {
      const cv::Size s = cv::getTextSize("+", kFont, scale_, thickness_, &base);
      cv::putText(image, "+", {x, origin.y - height_ / 6}, kFont, scale_, colour, thickness_, cv::LINE_AA);
      cv::line(image, {x + s.width / 6, origin.y}, {x + s.width * 5 / 6, origin.y}, colour, thickness_, cv::LINE_AA);
      x += s.width;
    } else if (p == kSquared) {
      const cv::Size s = cv::getTextSize("2", kFont, 0.6 * scale_, thickness_, &base);
      cv::putText(image, "2", {x, origin.y - static_cast<int>(0.45 * height_)}, kFont, 0.6 * scale_, colour, thickness_, cv::LINE_AA);
      x += s.width;
    } else if (!p.empty()) {
      cv::putText(image, p, {x, origin.y}, kFont, scale_, colour, thickness_, cv::LINE_AA);
      x += cv::getTextSize(p, kFont, scale_, thickness_, &base).width;
    }
  }
  const int descent = height_ / 3 + thickness_;
  return {origin.x, origin.y - height_ - thickness_, x - origin.x, height_ + thickness_ + descent};
}

std::vector<std::string> OverlayFont::wrap(const std::string& text, int max_width) const {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t comma = text.find(", "); comma != std::string::npos; comma = text.find(", ", start)) {
    parts.push_back(text.substr(start, comma + 1 - start));
    start = comma + 2;
  }
  parts.push_back(text.substr(start));
  std::vector<std::string> lines;
  for (const auto& part : parts) {
    if (!lines.empty() && width(lines.back() + " " + part) <= max_width) {
      lines.back() += " " + part;
    } else {
      lines.push_back(part);
    }
  }
  return lines;
}

}  // namespace stiffpath::vision::detail
