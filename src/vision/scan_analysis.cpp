// The scan measurement pipeline: coarse grid → mark → sides → cross-sections → px to m → evaluation metrics.
#include <algorithm>
#include <fmt/format.h>

#include "scan_internal.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision {

ScanResult analyse_scan(const cv::Mat& grey, double dpi, const ScanOptions& options) {
  const SourceLocation where{options.label, 0, 0};
  if (grey.empty() || grey.rows < 1 || grey.cols < 1) throw Error(where, "the image is empty");
  if (grey.channels() != 1 || (grey.depth() != CV_8U && grey.depth() != CV_16U)) {
    throw Error(where, "scan analysis needs a one-channel 8- or 16-bit image");
  }
  if (!(dpi > 0.0) || !std::isfinite(dpi)) throw Error(where, fmt::format("resolution must be positive, got {} dpi", dpi));
  if (options.sides < 1 || options.sides > 64) throw Error(where, fmt::format("number of sides must be 1..64, got {}", options.sides));
  if (options.cell_px < 2 || options.flank_px < 1 || options.baseline_window < 1 || !(options.band_margin_px >= 0)) {
    throw Error(where, "invalid scan options (cell >= 2 px, flank >= 1 px, baseline window >= 1, band margin >= 0)");
  }
  const double px_per_m = dpi / 0.0254;
  if (grey.rows < 4 * options.cell_px || grey.cols < 4 * options.cell_px) {
    throw Error(where, fmt::format("the image is too small to hold a mark ({} × {} px)", grey.cols, grey.rows));
  }

  ScanResult result;
  result.dpi = dpi;
  result.width_px = grey.cols;
  result.height_px = grey.rows;
  const detail::CoarseGrid grid = detail::build_coarse_grid(grey, options.cell_px);
  const detail::MarkComponent mark = detail::find_mark(grid, px_per_m, options);
  const detail::CoarsePath path = detail::find_sides(mark, options.sides, px_per_m, options);
  result.paper_noise = grid.sigma;
  result.specks_ignored = mark.specks;
  result.warnings = mark.warnings;

  std::vector<std::vector<Point2>> points;
  std::vector<double> widths;
  std::size_t sections = 0, rejected = 0;
  for (std::size_t k = 0; k < path.sides.size(); ++k) {
    detail::SideTrace trace = detail::trace_side(grey, grid, path, k, px_per_m, options);
    ScanSide s;
    if (trace.start_cap) s.centres.push_back(*trace.start_cap / px_per_m);
    for (const auto& c : trace.centres) s.centres.push_back(c / px_per_m);
    if (trace.end_cap) s.centres.push_back(*trace.end_cap / px_per_m);
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
  std::nth_element(widths.begin(), widths.begin() + static_cast<std::ptrdiff_t>(widths.size() / 2), widths.end());
  result.width_m = widths[widths.size() / 2];
  result.metrics = evaluation::measure_sides(points, path.closed, options.metrics);
  for (auto& corner : result.metrics.corners) corner.path_distance_m.reset();  // corner zones are not traced on scans
  if (result.specks_ignored > 0) result.warnings.push_back(fmt::format("ignored {} dust speck(s)", result.specks_ignored));
  if (rejected > sections / 100) {
    result.warnings.push_back(fmt::format("{} of {} cross-sections were left out as outliers (dust on the mark, gaps, or bends too sharp for the cross-sections)",
                                          rejected, sections));
  }
  return result;
}

}  // namespace stiffpath::vision
