// Drawing the overlay: legend and scale bar, the scan with centre line, fitted lines, splines, corners and side numbers, deviation strips.
#include "stiffpath/vision/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "overlay_text.hpp"

namespace stiffpath::vision {

namespace {

constexpr int kShift = 4;                 // sub-pixel drawing: coordinates × 16
constexpr double kMaxScanPixels = 25e6;   // larger scans are drawn smaller
const cv::Scalar kGreen{60, 170, 60}, kBlue{220, 90, 20}, kRed{40, 40, 230}, kYellow{0, 200, 230}, kGrey{140, 140, 140},
    kOrange{0, 140, 255}, kInk{30, 30, 30}, kWhite{255, 255, 255};

// 1, 2 or 5 × 10^k: the nice number nearest above `x`.
double nice_above(double x) {
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

class Canvas {
 public:
  Canvas(const cv::Mat& grey, double dpi, OverlayLayout* layout) : px_per_m_(dpi / 0.0254) {
    const double pixels = static_cast<double>(grey.cols) * grey.rows;
    s_ = std::min(1.0, std::sqrt(kMaxScanPixels / pixels));
    scan_size_ = {std::max(1, static_cast<int>(std::lround(grey.cols * s_))), std::max(1, static_cast<int>(std::lround(grey.rows * s_)))};
    h_ = std::clamp(static_cast<int>(std::lround(std::max(scan_size_.width, scan_size_.height) / 80.0)), 14, 160);
    font_ = detail::OverlayFont(h_);
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
  [[nodiscard]] const detail::OverlayFont& font() const { return font_; }
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
  detail::OverlayFont font_{14};
  OverlayLayout* layout_ = nullptr;
  OverlayLayout own_;
  std::vector<Item> items_;
  std::vector<std::pair<int, int>> places_;
  cv::Point scan_at_;
  cv::Mat image_;
};

// One side's strip: caption, the offset of the spline (red) and centre points (grey) from the fitted
// line (blue) magnified, ticks in mm along the side, the offset's scale in µm.
struct Strip {
  const evaluation::SideMetrics* side;
  const ScanSide* points;
  std::string caption;
};

int strip_height(const Canvas& c, const Strip& s) {
  const int lines = static_cast<int>(c.font().wrap(s.caption, c.width() - 2 * c.h()).size());
  // caption (h/2 above, 1.7 h a line), h/2, the plot, tick labels (1.7 h to their baseline, h/3 below)
  return lines * 17 * c.h() / 10 + std::max(5 * c.h(), 80) + 7 * c.h() / 2;
}

void draw_strip(Canvas& c, const Strip& s, int top) {
  const int h = c.h();
  cv::Mat& img = c.image();
  cv::line(img, {0, top}, {c.width() - 1, top}, kGrey, 1);
  int y = top + h / 2;
  for (const auto& line : c.font().wrap(s.caption, c.width() - 2 * h)) {
    y += 17 * h / 10;
    c.text(line, {h, y}, kInk);
  }
  const evaluation::SideMetrics& side = *s.side;
  const double peak = std::max(side.max_deviation_m, 1e-7);
  const double half_um = nice_above(1.1 * peak * 1e6);
  const std::string scale_text = fmt::format("\xC2\xB1{:g} \xC2\xB5m", half_um);  // "±… µm"
  const int left = h + c.font().width(scale_text) + h;
  const cv::Rect plot(left, y + h / 2, c.width() - left - h, std::max(5 * h, 80));
  c.layout().strips.push_back(plot);
  const int mid = plot.y + plot.height / 2;
  const double span = std::max(side.t_to_m - side.t_from_m, 1e-12);
  const double along = plot.width / span;                  // canvas px per m along the side
  const double gain = (plot.height / 2.0) / (half_um * 1e-6);  // canvas px per m of offset
  // The offset's scale: a bracket over the plot's height.
  cv::line(img, {left - h / 2, plot.y}, {left - h / 2, plot.y + plot.height}, kInk, c.lt());
  for (const int yy : {plot.y, plot.y + plot.height}) cv::line(img, {left - h / 2, yy}, {left - h / 4, yy}, kInk, c.lt());
  c.text(scale_text, {h / 2, mid + h / 2}, kInk);
  cv::line(img, {plot.x, mid}, {plot.x + plot.width, mid}, kBlue, c.lt(), cv::LINE_AA);
  auto point = [&](double t, double u) {
    const double px = plot.x + (t - side.t_from_m) * along, py = mid - std::clamp(u, -1.2 * half_um * 1e-6, 1.2 * half_um * 1e-6) * gain;
    return cv::Point(static_cast<int>(std::lround(px * (1 << kShift))), static_cast<int>(std::lround(py * (1 << kShift))));
  };
  for (const auto& p : s.points->centres) {
    const double t = side.fit.line.along(p);
    if (t >= side.t_from_m && t <= side.t_to_m) cv::circle(img, point(t, side.fit.line.offset(p)), std::max(1, c.lt() / 2) << kShift, kGrey, -1, cv::LINE_AA, kShift);
  }
  std::vector<cv::Point> curve;
  for (int i = 0; i <= 2000; ++i) {
    const double t = side.t_from_m + span * i / 2000.0;
    curve.push_back(point(t, side.spline.value(t)));
  }
  cv::polylines(img, curve, false, kRed, std::max(2, c.lt()), cv::LINE_AA, kShift);
  // Ticks along the side, from its start (mm).
  const double step_mm = nice_above(span * 1e3 / 8);
  const double start = side.fit.line.along(side.start);  // t of the side's start
  const double dir = side.t_to_m > side.t_from_m ? 1.0 : -1.0;
  for (double d = std::ceil((side.t_from_m - start) * 1e3 / step_mm) * step_mm; (start + d * 1e-3) * dir <= side.t_to_m * dir + 1e-12; d += step_mm) {
    const int x = static_cast<int>(std::lround(plot.x + (start + d * 1e-3 - side.t_from_m) * along));
    if (x < plot.x || x > plot.x + plot.width) continue;
    cv::line(img, {x, plot.y + plot.height}, {x, plot.y + plot.height + h / 3}, kInk, c.lt());
    const std::string label = fmt::format("{:g}", std::abs(d) < 1e-9 ? 0.0 : d);
    const int w = c.font().width(label);
    if (x + w / 2 < c.width() - h) c.text(label, {std::max(0, x - w / 2), plot.y + plot.height + 17 * h / 10}, kInk);
  }
  c.text("mm", {left - h - c.font().width("mm"), plot.y + plot.height + 17 * h / 10}, kInk);
}

std::string caption(const ScanResult& r, std::size_t k, int mark_index) {
  const auto& side = r.metrics.sides[k];
  const std::string who = mark_index > 0 ? fmt::format("mark {} side {}", mark_index, k + 1) : fmt::format("side {}", k + 1);
  return fmt::format("{}: length {:.4f} mm, deviation area {:.4f} mm\xC2\xB2, max deviation {:.4f} mm, straightness {:.4f} mm, "
                     "width {:.4f} mm", who, side.length_m * 1e3, side.deviation_area_m2 * 1e6, side.max_deviation_m * 1e3,
                     side.straightness_m * 1e3, r.sides[k].width_m * 1e3);
}

// The mark's lines on the scan and its sides' numbers (outside a loop, or on the sides' normal side).
void draw_mark(Canvas& c, const ScanResult& r, int mark_index) {
  const auto& sides = r.metrics.sides;
  Point2 centroid{0, 0};
  for (const auto& s : sides) centroid += (s.start + s.end) / (2.0 * static_cast<double>(sides.size()));
  for (std::size_t k = 0; k < sides.size(); ++k) {
    const auto& side = sides[k];
    c.polyline_m(r.sides[k].centres, kGreen);
    c.polyline_m({side.start, side.end}, kBlue);
    std::vector<Point2> spline;
    const double step = 2.0 / c.canvas_px_per_m();
    for (double t = side.t_from_m; t <= side.t_to_m; t += step) spline.push_back(side.fit.line.at(t, side.spline.value(t)));
    c.polyline_m(spline, kRed);
    const Point2 mid = (side.start + side.end) / 2;
    Point2 normal = side.fit.line.normal();
    if (r.metrics.closed && normal.dot(mid - centroid) < 0) normal = -normal;
    const Point2 label_at = mid + normal * (2.0 * c.h() / c.canvas_px_per_m());
    if (sides.size() > 1 || mark_index == 0) c.disc(mark_index > 0 ? fmt::format("{}.{}", mark_index, k + 1) : std::to_string(k + 1), c.at(label_at));
  }
  for (const auto& corner : r.metrics.corners) c.circle_m(corner.position, kYellow);
}

std::vector<Item> legend_items(bool plate) {
  std::vector<Item> items{{Item::line, kGreen, "centre line"},       {Item::line, kBlue, "fitted line"},
                          {Item::line, kRed, "smoothing spline"},    {Item::dots, kGrey, "centre points (strips)"},
                          {Item::circle, kYellow, "corner"}};
  if (plate) {
    items.push_back({Item::box, kGreen, "measured mark"});
    items.push_back({Item::box, kOrange, "skipped mark"});
    items.push_back({Item::box, kGrey, "label (not measured)"});
  }
  return items;
}

}  // namespace

cv::Mat draw_overlay(const cv::Mat& grey, const ScanResult& result, OverlayLayout* layout) {
  Canvas c(grey, result.dpi, layout);
  const int top = c.plan_legend(legend_items(false));
  std::vector<Strip> strips;
  for (std::size_t k = 0; k < result.metrics.sides.size(); ++k) strips.push_back({&result.metrics.sides[k], &result.sides[k], caption(result, k, 0)});
  const int scan_h = static_cast<int>(std::lround(grey.rows * c.layout().scale));
  int height = top + std::max(1, scan_h);
  for (const auto& s : strips) height += strip_height(c, s);
  c.allocate(height, grey, top);
  c.draw_legend();
  draw_mark(c, result, 0);
  int y = top + std::max(1, scan_h);
  for (const auto& s : strips) {
    draw_strip(c, s, y);
    y += strip_height(c, s);
  }
  return c.image();
}

cv::Mat draw_plate_overlay(const cv::Mat& grey, const PlateResult& plate, OverlayLayout* layout) {
  Canvas c(grey, plate.dpi, layout);
  const int top = c.plan_legend(legend_items(true));
  std::vector<Strip> strips;
  std::vector<std::string> skipped;
  for (const auto& m : plate.marks) {
    if (!m.measured) {
      skipped.push_back(fmt::format("mark {}: skipped, {}", m.index, m.reason));
      continue;
    }
    for (std::size_t k = 0; k < m.result.metrics.sides.size(); ++k) {
      strips.push_back({&m.result.metrics.sides[k], &m.result.sides[k], caption(m.result, k, m.index)});
    }
  }
  const int scan_h = static_cast<int>(std::lround(grey.rows * c.layout().scale));
  int height = top + std::max(1, scan_h);
  for (const auto& s : strips) height += strip_height(c, s);
  int list_lines = 0;
  for (const auto& line : skipped) list_lines += static_cast<int>(c.font().wrap(line, c.width() - 2 * c.h()).size());
  if (list_lines > 0) height += list_lines * 17 * c.h() / 10 + c.h();
  c.allocate(height, grey, top);
  c.draw_legend();
  for (const auto& l : plate.labels) {
    const int pad = c.h() / 3;
    cv::rectangle(c.image(), c.at({l.box_m.x, l.box_m.y}) - cv::Point(pad, pad),
                  c.at({l.box_m.x + l.box_m.width, l.box_m.y + l.box_m.height}) + cv::Point(pad, pad), kGrey, c.lt());
  }
  for (const auto& m : plate.marks) {
    const cv::Point a = c.at({m.box_m.x, m.box_m.y}), b = c.at({m.box_m.x + m.box_m.width, m.box_m.y + m.box_m.height});
    const int pad = c.h() / 3;
    const cv::Rect box(a - cv::Point(pad, pad), b + cv::Point(pad, pad));
    cv::rectangle(c.image(), box, m.measured ? kGreen : kOrange, c.lt());
    const std::string label = fmt::format("mark {}", m.index);
    const int label_y = box.y > c.layout().scan.y + 3 * c.h() / 2 ? box.y - c.h() / 3 : box.y + box.height + 4 * c.h() / 3;
    c.text(label, {std::clamp(box.x, 0, std::max(0, c.width() - c.font().width(label))), label_y}, m.measured ? kGreen : kOrange);
    if (m.measured) draw_mark(c, m.result, m.index);
  }
  int y = top + std::max(1, scan_h);
  for (const auto& s : strips) {
    draw_strip(c, s, y);
    y += strip_height(c, s);
  }
  if (list_lines > 0) {
    cv::line(c.image(), {0, y}, {c.width() - 1, y}, kGrey, 1);
    y += c.h() / 2;
    for (const auto& line : skipped) {
      for (const auto& piece : c.font().wrap(line, c.width() - 2 * c.h())) {
        y += 17 * c.h() / 10;
        c.text(piece, {c.h(), y}, kOrange);
      }
    }
  }
  return c.image();
}

}  // namespace stiffpath::vision
