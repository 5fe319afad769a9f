// The scan measurement pipeline: coarse grid → mark → sides → cross-sections → px to m → evaluation metrics.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "scan_internal.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/median.hpp"

namespace stiffpath::vision {

namespace detail {

std::string position_text(const Point2& px, double px_per_m, const ScanOptions& o) {
  const Point2 at = px + Point2{o.roi_px.x, o.roi_px.y};
  return fmt::format("x = {:.2f} mm, y = {:.2f} mm", at.x() / px_per_m * 1e3, at.y() / px_per_m * 1e3);
}

void check_scan_input(const cv::Mat& grey, double dpi, const ScanOptions& options) {
  const SourceLocation where{options.label, 0, 0};
  if (grey.empty() || grey.rows < 1 || grey.cols < 1) throw Error(where, "the image is empty");
  if (grey.channels() != 1 || (grey.depth() != CV_8U && grey.depth() != CV_16U)) {
    throw Error(where, "scan analysis needs a one-channel 8- or 16-bit image");
  }
  if (!(dpi > 0.0) || !std::isfinite(dpi)) throw Error(where, fmt::format("resolution must be positive, got {} dpi", dpi));
  if (options.sides < 0 || options.sides > 64) throw Error(where, fmt::format("number of sides must be 0 (any) or 1..64, got {}", options.sides));
  const ScanTuning& t = options.tuning;
  if (t.cell_px < 2 || t.cell_px > 64 || t.paper_block_cells < 1 || t.flank_px < 1 || t.flank_px > 64 || t.paper_window_sections < 1 ||
      !(t.window_margin_px >= 0) || t.ransac_trials < 1 || t.slope_half_window_sections < 1 || t.outlier_neighbours < 1) {
    throw Error(where, "invalid scan tuning (cell 2..64 px, paper block >= 1 cell, flank 1..64 px, paper window >= 1 section, "
                       "window margin >= 0 px, RANSAC trials >= 1, slope and outlier windows >= 1 section)");
  }
  const cv::Rect& roi = options.roi_px;
  if (!roi.empty() && (roi & cv::Rect(0, 0, grey.cols, grey.rows)) != roi) {
    throw Error(where, fmt::format("the region x {}..{} px, y {}..{} px reaches beyond the image ({} × {} px)", roi.x,
                                   roi.x + roi.width, roi.y, roi.y + roi.height, grey.cols, grey.rows));
  }
  const cv::Size size = roi.empty() ? grey.size() : roi.size();
  if (size.height < 4 * t.cell_px || size.width < 4 * t.cell_px) {
    throw Error(where, fmt::format("the {} is too small to hold a mark ({} × {} px)", roi.empty() ? "image" : "region",
                                   size.width, size.height));
  }
}

CoarsePath find_path(const MarkComponent& mark, double px_per_m, const ScanOptions& options) {
  if (options.sides > 0) return find_sides(mark, options.sides, px_per_m, options);
  // Any shape: a straight line, else the fewest straight sides that join into one chain or loop.
  for (int n = 1; n <= options.max_auto_sides; ++n) {
    try {
      return find_sides(mark, n, px_per_m, options);
    } catch (const Error&) {
      continue;
    }
  }
  throw Error(SourceLocation{options.label, 0, 0},
              fmt::format("the mark is neither a straight line nor one chain or loop of up to {} straight sides", options.max_auto_sides));
}

ScanResult measure_mark(const cv::Mat& grey, const CoarseGrid& grid, const MarkComponent& mark, double px_per_m,
                        const ScanOptions& options) {
  const CoarsePath path = find_path(mark, px_per_m, options);
  ScanResult result;
  result.paper_noise = grid.sigma;
  result.specks_ignored = mark.specks;
  result.warnings = mark.warnings;
  const Point2 origin{options.roi_px.x, options.roi_px.y};  // positions in the whole image's frame
  std::vector<std::vector<Point2>> points;
  std::vector<double> widths;
  std::size_t sections = 0, rejected = 0;
  for (std::size_t k = 0; k < path.sides.size(); ++k) {
    SideTrace trace = trace_side(grey, grid, path, k, px_per_m, options);
    if (options.progress) options.progress(0.3 + 0.7 * static_cast<double>(k + 1) / static_cast<double>(path.sides.size()));
    ScanSide s;
    if (trace.start_cap) s.centres.push_back((*trace.start_cap + origin) / px_per_m);
    for (const auto& c : trace.centres) s.centres.push_back((c + origin) / px_per_m);
    if (trace.end_cap) s.centres.push_back((*trace.end_cap + origin) / px_per_m);
    s.width_m = trace.width / px_per_m;
    s.sections = trace.sections;
    s.rejected_sections = trace.rejected;
    sections += trace.sections;
    rejected += trace.rejected;
    for (const double w : trace.widths) widths.push_back(w / px_per_m);
    result.length_uncertainty_m += trace.end_uncertainty / px_per_m;
    result.mark_darkness += trace.darkness / static_cast<double>(path.sides.size());
    result.warnings.insert(result.warnings.end(), trace.warnings.begin(), trace.warnings.end());
    points.push_back(s.centres);
    result.sides.push_back(std::move(s));
  }
  result.width_m = core::median_in_place(std::span<double>(widths), core::MedianRule::upper_middle);  // as each side's width
  result.metrics = evaluation::measure_sides(points, path.closed, options.metrics);
  for (auto& corner : result.metrics.corners) corner.path_distance_m.reset();  // corner zones are not traced on scans
  if (result.specks_ignored > 0) result.warnings.push_back(fmt::format("ignored {} dust speck(s)", result.specks_ignored));
  if (rejected > sections / 100) {
    result.warnings.push_back(fmt::format("{} of {} cross-sections were left out as outliers (dust on the mark, gaps, or bends "
                                          "too sharp for the cross-sections)", rejected, sections));
  }
  return result;
}

}  // namespace detail

ScanResult analyse_scan(const cv::Mat& grey, double dpi, const ScanOptions& options) {
  detail::check_scan_input(grey, dpi, options);
  const double px_per_m = dpi / 0.0254;
  const cv::Mat view = options.roi_px.empty() ? grey : grey(options.roi_px);
  const detail::CoarseGrid grid = detail::build_coarse_grid(view, options.tuning);
  if (options.progress) options.progress(0.3);
  const detail::MarkComponent mark = detail::find_mark(grid, px_per_m, options);
  ScanResult result = detail::measure_mark(view, grid, mark, px_per_m, options);
  result.dpi = dpi;
  result.width_px = grey.cols;
  result.height_px = grey.rows;
  return result;
}

std::string shape_name(const ScanResult& result) {
  const std::size_t n = result.metrics.sides.size();
  if (n == 1) return "line";
  if (n == 3 && result.metrics.closed) return "triangle";
  return fmt::format("polyline:{}", n);
}

}  // namespace stiffpath::vision
