// The overlay's canvas: scale, text size, legend with scale bar, the scan's place, drawing in scan coordinates; not installed.
#pragma once

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "overlay_text.hpp"
#include "stiffpath/vision/scan/overlay.hpp"

namespace stiffpath::vision::detail {

inline constexpr int kShift = 4;                 // sub-pixel drawing: coordinates × 16
inline constexpr double kMaxScanPixels = 25e6;   // larger scans are drawn smaller
inline const cv::Scalar kGreen{60, 170, 60}, kBlue{220, 90, 20}, kRed{40, 40, 230}, kYellow{0, 200, 230}, kGrey{140, 140, 140},
    kOrange{0, 140, 255}, kInk{30, 30, 30}, kWhite{255, 255, 255};

// 1, 2 or 5 × 10^k: the nice number nearest above `x`.
inline double nice_above(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= x * (1 - 1e-9)) return m * p;
  }
  return 10 * p;
}

struct Item {  // a legend entry: a swatch and its text
  enum Kind { line, dots, circle, box, bar } kind;
  cv::Scalar colour;
  std::string text;
};

//! The picture being drawn: it decides the scale (scans above kMaxScanPixels shrink), the text height
//! (1/80 of the scan's larger side, 14–160 px), the line width and the picture's width (at least 44
//! text heights), lays out the legend, places the scan and draws in scan coordinates (m).
class Canvas {
 public:
  Canvas(const cv::Mat& grey, double dpi, OverlayLayout* layout) : px_per_m_(dpi / 0.0254) {
    const double pixels = static_cast<double>(grey.cols) * grey.rows;
    s_ = std::min(1.0, std::sqrt(kMaxScanPixels / pixels));
    scan_size_ = {std::max(1, static_cast<int>(std::lround(grey.cols * s_))), std::max(1, static_cast<int>(std::lround(grey.rows * s_)))};
    h_ = std::clamp(static_cast<int>(std::lround(std::max(scan_size_.width, scan_size_.height) / 80.0)), 14, 160);
    font_ = OverlayFont(h_);
    lt_ = std::max(1, static_cast<int>(std::lround(h_ / 14.0)));
    width_ = std::max(scan_size_.width, 44 * h_);
    layout_ = layout != nullptr ? layout : &own_;
    *layout_ = OverlayLayout{};
    layout_->scale = s_;
    layout_->text_height_px = h_;
  }

  [[nodiscard]] int h() const { return h_; }
  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int lt() const { return lt_; }
  [[nodiscard]] const OverlayFont& font() const { return font_; }
  [[nodiscard]] double canvas_px_per_m() const { return px_per_m_ * s_; }
  [[nodiscard]] OverlayLayout& layout() { return *layout_; }

  // Lays out the legend (flowing into rows) and returns its height.
  int plan_legend(std::vector<Item> items) {
    items_ = std::move(items);
    const double bar_mm = nice_above(width_ / 6.0 / canvas_px_per_m() * 1e3 / 2);
    bar_mm_ = bar_mm;
    bar_px_ = static_cast<int>(std::lround(bar_mm * 1e-3 * canvas_px_per_m()));
    items_.push_back({Item::bar, kInk, fmt::format("{:g} mm", bar_mm)});
    if (s_ < 1.0) items_.push_back({Item::box, kWhite, fmt::format("scan shown at {:.0f} %", 100 * s_)});
    int x = h_, rows = 1;
    places_.clear();
    for (const auto& item : items_) {
      const int w = swatch_width(item) + h_ / 2 + font_.width(item.text);
      if (x > h_ && x + w > width_ - h_) x = h_, ++rows;
      places_.emplace_back(x, rows - 1);
      x += w + 3 * h_ / 2;
    }
    legend_height_ = rows * 2 * h_ + h_;
    return legend_height_;
  }

  void allocate(int height, const cv::Mat& grey, int scan_top) {
    image_ = cv::Mat(height, width_, CV_8UC3, kWhite);
    layout_->size = image_.size();
    scan_at_ = {(width_ - scan_size_.width) / 2, scan_top};
    layout_->scan = cv::Rect(scan_at_, scan_size_);
    // Shrunk first, then made 8-bit and colour: no full-size copy of a large scan.
    cv::Mat small = grey, grey8;
    if (s_ < 1.0) cv::resize(grey, small, scan_size_, 0, 0, cv::INTER_AREA);
    if (small.depth() == CV_16U) {
      small.convertTo(grey8, CV_8U, 1.0 / 257.0);
    } else {
      grey8 = small;
    }
    cv::cvtColor(grey8, image_(layout_->scan), cv::COLOR_GRAY2BGR);
  }

  void draw_legend() {
    for (std::size_t i = 0; i < items_.size(); ++i) {
      const Item& item = items_[i];
      const int x = places_[i].first, y = h_ + places_[i].second * 2 * h_ + h_;  // text baseline
      const int sw = swatch_width(item), mid = y - h_ / 2;
      switch (item.kind) {
        case Item::line: cv::line(image_, {x, mid}, {x + sw, mid}, item.colour, std::max(2, lt_), cv::LINE_AA); break;
        case Item::dots:
          for (int k = 0; k < 4; ++k) cv::circle(image_, {x + h_ / 3 + k * (sw - 2 * h_ / 3) / 3, mid}, std::max(2, lt_), item.colour, -1, cv::LINE_AA);
          break;
        case Item::circle: cv::circle(image_, {x + sw / 2, mid}, h_ / 2, item.colour, std::max(2, lt_), cv::LINE_AA); break;
        case Item::box: cv::rectangle(image_, {x, y - h_}, {x + sw, y}, item.colour, std::max(2, lt_)); break;
        case Item::bar: {
          cv::line(image_, {x, mid}, {x + bar_px_, mid}, kInk, std::max(2, lt_));
          for (const int end : {x, x + bar_px_}) cv::line(image_, {end, mid - h_ / 2}, {end, mid + h_ / 2}, kInk, std::max(2, lt_));
          layout_->scale_bar = cv::Rect(x, mid - h_ / 2, bar_px_ + 1, h_ + 1);
          layout_->scale_bar_mm = bar_mm_;
          break;
        }
      }
      text(item.text, {x + sw + h_ / 2, y}, kInk);
      layout_->legend_entries.push_back(item.text);
    }
    layout_->legend = cv::Rect(0, 0, width_, legend_height_);
    cv::line(image_, {0, legend_height_ - 1}, {width_ - 1, legend_height_ - 1}, kGrey, 1);
  }

  cv::Rect text(const std::string& t, cv::Point origin, const cv::Scalar& colour) {
    const cv::Rect box = font_.draw(image_, t, origin, colour);
    layout_->texts.push_back({t, box});
    return box;
  }

  // A point of the scan (m, image frame) on the canvas, in OpenCV's fixed-point pixel-centre convention.
  [[nodiscard]] cv::Point fixed(const Point2& m) const {
    const Point2 p = m * canvas_px_per_m() + Point2{scan_at_.x, scan_at_.y} - Point2{0.5, 0.5};
    return {static_cast<int>(std::lround(p.x() * (1 << kShift))), static_cast<int>(std::lround(p.y() * (1 << kShift)))};
  }
  [[nodiscard]] cv::Point at(const Point2& m) const {
    const cv::Point f = fixed(m);
    return {f.x >> kShift, f.y >> kShift};
  }

  void polyline_m(const std::vector<Point2>& pts_m, const cv::Scalar& colour) {
    std::vector<cv::Point> p;
    for (const auto& q : pts_m) p.push_back(fixed(q));
    if (p.size() >= 2) cv::polylines(image_, p, false, colour, lt_, cv::LINE_AA, kShift);
  }
  void circle_m(const Point2& m, const cv::Scalar& colour) {
    cv::circle(image_, fixed(m), (h_ / 2) << kShift, colour, std::max(2, lt_), cv::LINE_AA, kShift);
  }

  // A numbered disc at `centre` (canvas px), kept within the rows of the scan (beside a narrow scan it
  // may sit on the white margin).
  void disc(const std::string& label, cv::Point centre) {
    const int r = std::max(h_ * 6 / 10, font_.width(label) / 2 + h_ / 4);
    const cv::Rect& s = layout_->scan;
    centre.x = std::clamp(centre.x, r + lt_, width_ - r - lt_ - 1);
    centre.y = std::clamp(centre.y, s.y + r + lt_, std::max(s.y + r + lt_, s.y + s.height - r - lt_ - 1));
    cv::circle(image_, centre, r, kWhite, -1, cv::LINE_AA);
    cv::circle(image_, centre, r, kInk, lt_, cv::LINE_AA);
    text(label, {centre.x - font_.width(label) / 2, centre.y + h_ / 2}, kInk);
    layout_->side_numbers.emplace_back(centre.x - r, centre.y - r, 2 * r + 1, 2 * r + 1);
  }

  cv::Mat& image() { return image_; }
  [[nodiscard]] cv::Point scan_at() const { return scan_at_; }

 private:
  [[nodiscard]] int swatch_width(const Item& item) const { return item.kind == Item::bar ? bar_px_ : 2 * h_; }

  double px_per_m_, s_ = 1;
  cv::Size scan_size_;
  int h_ = 14, lt_ = 1, width_ = 0, legend_height_ = 0, bar_px_ = 0;
  double bar_mm_ = 0;
  OverlayFont font_{14};
  OverlayLayout* layout_ = nullptr;
  OverlayLayout own_;
  std::vector<Item> items_;
  std::vector<std::pair<int, int>> places_;
  cv::Point scan_at_;
  cv::Mat image_;
};

}  // namespace stiffpath::vision::detail
