// Drawing the overlay: centre line, fitted lines, splines and corners on the scan, plus magnified deviation strips.
#include "stiffpath/vision/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

namespace stiffpath::vision {

namespace {

constexpr int kShift = 4;  // sub-pixel drawing: coordinates × 16
constexpr int kStrip = 140;
const cv::Scalar kGreen{60, 200, 60}, kBlue{220, 90, 20}, kRed{40, 40, 230}, kYellow{0, 210, 230}, kGrey{150, 150, 150};

cv::Point fixed(const Point2& px) {
  // Our pixel (c, r) spans [c, c+1); OpenCV puts pixel centres at integers.
  return {static_cast<int>(std::lround((px.x() - 0.5) * (1 << kShift))), static_cast<int>(std::lround((px.y() - 0.5) * (1 << kShift)))};
}

void polyline(cv::Mat& img, const std::vector<Point2>& pts_px, const cv::Scalar& colour) {
  std::vector<cv::Point> p;
  for (const auto& q : pts_px) p.push_back(fixed(q));
  if (p.size() >= 2) cv::polylines(img, p, false, colour, 1, cv::LINE_AA, kShift);
}

void label(cv::Mat& img, const std::string& text, cv::Point at) {
  cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(30, 30, 30), 1, cv::LINE_AA);
}

}  // namespace

cv::Mat draw_overlay(const cv::Mat& grey, const ScanResult& result) {
  const double px_per_m = result.dpi / 0.0254;
  const int strips = static_cast<int>(result.metrics.sides.size());
  cv::Mat out(grey.rows + strips * kStrip, grey.cols, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::Mat grey8;
  grey.convertTo(grey8, CV_8U, grey.depth() == CV_16U ? 1.0 / 257.0 : 1.0);
  cv::cvtColor(grey8, out(cv::Rect(0, 0, grey.cols, grey.rows)), cv::COLOR_GRAY2BGR);
  for (std::size_t k = 0; k < result.metrics.sides.size(); ++k) {
    const auto& side = result.metrics.sides[k];
    const auto& line = side.fit.line;
    std::vector<Point2> centres, fitted{side.start * px_per_m, side.end * px_per_m}, spline;
    for (const auto& c : result.sides[k].centres) centres.push_back(c * px_per_m);
    const double step = 2.0 / px_per_m;
    for (double t = side.t_from_m; t <= side.t_to_m; t += step) spline.push_back(line.at(t, side.spline.value(t)) * px_per_m);
    polyline(out, centres, kGreen);
    polyline(out, fitted, kBlue);
    polyline(out, spline, kRed);

    // Deviation strip: t across the picture's width, offset magnified to fill the strip.
    const int top = grey.rows + static_cast<int>(k) * kStrip, mid = top + kStrip / 2;
    const double span = std::max(side.t_to_m - side.t_from_m, 1e-12);
    const double peak = std::max(side.max_deviation_m, 1e-7);
    const double gain = (kStrip / 2.0 - 18) / peak;  // px of strip per m of offset
    auto strip_point = [&](double t, double u) {
      return Point2{4 + (grey.cols - 8) * (t - side.t_from_m) / span + 0.5, mid - u * gain + 0.5};
    };
    cv::line(out, cv::Point(0, top), cv::Point(grey.cols - 1, top), kGrey, 1);
    cv::line(out, cv::Point(4, mid), cv::Point(grey.cols - 5, mid), kBlue, 1);
    for (const auto& c : result.sides[k].centres) {
      const double t = line.along(c), u = std::clamp(line.offset(c), -1.3 * peak, 1.3 * peak);
      if (t >= side.t_from_m && t <= side.t_to_m) cv::circle(out, fixed(strip_point(t, u)), 1 << kShift, kGrey, -1, cv::LINE_AA, kShift);
    }
    std::vector<Point2> curve;
    for (double t = side.t_from_m; t <= side.t_to_m; t += span / 2000) curve.push_back(strip_point(t, side.spline.value(t)));
    polyline(out, curve, kRed);
    label(out, fmt::format("side {}: deviation x{:.0f} (strip half-height {:.1f} um), length {:.4f} mm, area {:.4f} mm2, "
                           "max {:.4f} mm", k + 1, gain / px_per_m, (kStrip / 2.0) / gain * 1e6, side.length_m * 1e3,
                           side.deviation_area_m2 * 1e6, side.max_deviation_m * 1e3),
          cv::Point(6, top + 16));
  }
  for (const auto& corner : result.metrics.corners) {
    cv::circle(out, fixed(corner.position * px_per_m), static_cast<int>(6 << kShift), kYellow, 1, cv::LINE_AA, kShift);
  }
  return out;
}

}  // namespace stiffpath::vision
