// Drawing the overlay: legend and scale bar, the scan with centre line, fitted lines, splines, corners and side numbers, deviation strips.
#include "stiffpath/vision/scan/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "overlay_canvas.hpp"

namespace stiffpath::vision {

namespace {

using detail::Canvas;
using detail::Item;
using detail::kBlue, detail::kGreen, detail::kGrey, detail::kInk, detail::kOrange, detail::kRed, detail::kShift, detail::kYellow;
using detail::nice_above;

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
