// A scanned calibration plate: registered by its fiducials, each stroke's centre line measured in a corridor around its command (arcs: plate_arc.cpp).
#include "stiffpath/vision/scan/plate_marks.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "plate_arc.hpp"
#include "plate_registration.hpp"
#include "scan_internal.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/segment_distance.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::vision {

namespace {

constexpr double kPad_m = 1e-3;  // paper kept around a corridor, so the scan sees paper on every side of the mark

// Median and robust σ (1.4826 · MAD) of the crop's grey values: the paper's level and noise (the mark is a
// small part of a corridor's box).
std::pair<double, double> paper_level(const cv::Mat& crop) {
  cv::Mat f;
  crop.convertTo(f, CV_32F);
  std::vector<float> v(f.begin<float>(), f.end<float>());
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  const double median = *mid;
  for (auto& x : v) x = static_cast<float>(std::abs(x - median));
  std::nth_element(v.begin(), mid, v.end());
  return {median, 1.4826 * *mid};
}

// One stroke: its corridor cut out of the scan (paper-like noise outside it), measured, mapped to the robot frame.
// `work` is a copy of `grey`, reused by every stroke.
void observe_stroke(const calibration::StrokeMark& stroke, const cv::Mat& grey, cv::Mat& work, double dpi,
                    const std::string& label, const PlateScanOptions& options, PlateObservation& out) {
  const double px_per_m = dpi / 0.0254;
  const PlateRegistration& reg = out.registration;
  std::vector<Point2> command_px;  // the commanded path on the scan (px)
  for (const auto& p : stroke.polyline_m()) command_px.push_back(reg.to_scan(p) * px_per_m);
  const double half_px = options.corridor_half_width_m * px_per_m;
  const double reach_px = half_px + kPad_m * px_per_m;
  Point2 lo = command_px.front(), hi = command_px.front();
  for (const auto& p : command_px) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (lo.x() - half_px < 0 || lo.y() - half_px < 0 || hi.x() + half_px > grey.cols || hi.y() + half_px > grey.rows) {
    out.warnings.push_back(fmt::format("stroke {}: not measured: its corridor leaves the scan", stroke.id));
    return;
  }
  const cv::Rect box = cv::Rect(cv::Point(static_cast<int>(std::floor(lo.x() - reach_px)), static_cast<int>(std::floor(lo.y() - reach_px))),
                                cv::Point(static_cast<int>(std::ceil(hi.x() + reach_px)), static_cast<int>(std::ceil(hi.y() + reach_px)))) &
                       cv::Rect(0, 0, grey.cols, grey.rows);
  // The box copied into the working image, paper-like noise put outside the corridor: other marks are not seen.
  grey(box).copyTo(work(box));
  cv::Mat crop = work(box);
  // The corridor: every pixel within half_px of the command (drawn with 1/16 px precision, round ends).
  cv::Mat corridor = cv::Mat::zeros(crop.size(), CV_8U);
  std::vector<cv::Point> pts;
  for (const auto& p : command_px) pts.emplace_back(cvRound((p.x() - box.x - 0.5) * 16), cvRound((p.y() - box.y - 0.5) * 16));
  cv::polylines(corridor, std::vector<std::vector<cv::Point>>{pts}, false, cv::Scalar(255),
                2 * static_cast<int>(std::round(half_px)) + 1, cv::LINE_8, 4);
  const auto [paper, sigma] = paper_level(crop);
  cv::Mat fill(crop.size(), CV_32F);
  cv::RNG rng(0x5eed);
  rng.fill(fill, cv::RNG::NORMAL, paper, std::max(sigma, 0.5));
  fill.convertTo(fill, crop.type());  // saturating
  fill.copyTo(crop, corridor == 0);

  ScanOptions so;
  so.sides = stroke.kind == calibration::StrokeKind::ringing ? 2 : 1;
  so.label = fmt::format("{}: stroke {}", label, stroke.id);
  so.metrics.corner_trim_m = options.corner_trim_m;
  so.roi_px = box;  // positions stay in the whole scan's frame
  ScanResult result;
  try {
    result = analyse_scan(work, dpi, so);
  } catch (const Error& e) {
    out.warnings.push_back(fmt::format("stroke {}: not measured: {}", stroke.id, e.message()));
    return;
  }
  // Each side to the commanded segment it runs along, oriented as the command runs.
  const std::size_t segments = command_px.size() - 1;
  std::vector<std::vector<Point2>> along(segments);
  for (const auto& side : result.sides) {
    if (side.centres.size() < 2) continue;
    std::vector<Point2> pts_px;
    for (const auto& c : side.centres) pts_px.push_back(c * px_per_m);
    const Point2 dir = pts_px.back() - pts_px.front();
    std::size_t best = 0;
    double best_cos = -1;
    for (std::size_t k = 0; k < segments; ++k) {
      const Point2 d = command_px[k + 1] - command_px[k];
      const double c = std::abs(dir.dot(d)) / std::max(dir.norm() * d.norm(), 1e-300);
      if (c > best_cos) best_cos = c, best = k;
    }
    if (!along[best].empty()) {
      out.warnings.push_back(fmt::format("stroke {}: not measured: two of its sides run along the same commanded segment",
                                         stroke.id));
      return;
    }
    if (dir.dot(command_px[best + 1] - command_px[best]) < 0) std::reverse(pts_px.begin(), pts_px.end());
    along[best] = std::move(pts_px);
  }
  calibration::ObservedMark mark{stroke.id, {}};
  double farthest_px = 0;
  for (const auto& seg : along) {
    for (const auto& p : seg) {
      farthest_px = std::max(farthest_px, evaluation::polyline_distance(p, command_px));
      mark.points_m.push_back(reg.to_robot(p / px_per_m));
    }
  }
  if (mark.points_m.size() < 2) {
    out.warnings.push_back(fmt::format("stroke {}: not measured: no centre line found", stroke.id));
    return;
  }
  // A mark reaching the corridor's edge was cut there: its measured end is the corridor's, not the mark's.
  const double edge_px = half_px - 0.5 * result.width_m * px_per_m - 2.0;
  if (farthest_px > edge_px) {
    out.warnings.push_back(fmt::format("stroke {}: cut short: its centre line runs {:.3f} mm from the command, to the "
                                       "corridor's edge ({:.3f} mm wide on each side)",
                                       stroke.id, farthest_px / px_per_m * 1e3, options.corridor_half_width_m * 1e3));
  }
  for (const auto& w : result.warnings) out.warnings.push_back(fmt::format("stroke {}: {}", stroke.id, w));
  out.marks.push_back(std::move(mark));
}

}  // namespace

PlateObservation observe_calibration_plate(const calibration::PlateDesign& plate, const cv::Mat& grey, double dpi,
                                           const std::string& label, const PlateScanOptions& options) {
  if (!(options.corridor_half_width_m >= 0.2e-3 && options.corridor_half_width_m <= 10e-3)) {
    throw Error(fmt::format("{}: the corridor's half-width must be 0.2 … 10 mm, not {} m", label, options.corridor_half_width_m));
  }
  if (!(options.max_residual_m > 0 && options.max_residual_m <= 1e-3)) {
    throw Error(fmt::format("{}: the largest registration residual must be in (0, 1] mm, not {} m", label, options.max_residual_m));
  }
  if (!(options.min_ink_margin > 0 && options.min_ink_margin <= 1)) {
    throw Error(fmt::format("{}: the ink margin must be in (0, 1], not {}", label, options.min_ink_margin));
  }
  if (grey.empty() || grey.channels() != 1 || (grey.depth() != CV_8U && grey.depth() != CV_16U)) {
    throw Error(fmt::format("{}: a plate scan must be a grey image of 8 or 16 bits", label));
  }
  PlateObservation out;
  out.registration = detail::register_plate(plate, grey, dpi, label, options);
  cv::Mat work = grey.clone();
  for (const auto& stroke : plate.strokes) {
    if (stroke.kind != calibration::StrokeKind::arc) {
      observe_stroke(stroke, grey, work, dpi, label, options, out);
      continue;
    }
    std::string why;
    auto points = detail::measure_arc(stroke, grey, dpi, out.registration, options.corridor_half_width_m,
                                      options.corner_trim_m, why);
    if (points.empty()) {
      out.warnings.push_back(fmt::format("arc {}: not measured: {}", stroke.id, why));
    } else {
      out.marks.push_back({stroke.id, std::move(points)});
    }
  }
  return out;
}

PlateObservation observe_calibration_plate(const calibration::PlateDesign& plate, const std::filesystem::path& scan,
                                           const PlateScanOptions& options) {
  const ScanImage image = options.dpi > 0 ? load_scan(scan, options.dpi) : load_scan(scan);
  if (image.dpi_source == "default") {
    // A plate's scale comes from the resolution: an assumed one would register nothing.
    throw Error(fmt::format("{}: the file stores no resolution; give the scan's resolution (dpi) to register the plate",
                            scan.string()));
  }
  PlateObservation out = observe_calibration_plate(plate, image.grey, image.dpi, scan.string(), options);
  out.warnings.insert(out.warnings.begin(), image.warnings.begin(), image.warnings.end());
  return out;
}

}  // namespace stiffpath::vision
