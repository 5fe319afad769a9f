// Where a side's cross-sections go: body sections between its corners' trims or short of its free ends, end sections beyond.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "side_trace.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision::detail {

SideSections lay_out_sections(const cv::Mat& grey, const CoarseGrid& grid, const CoarsePath& path, std::size_t index,
                              double px_per_m, const ScanOptions& options, std::vector<std::string>& warnings) {
  const ScanTuning& tuning = options.tuning;
  const CoarseSide& coarse = path.sides[index];
  const evaluation::Line2& line = coarse.line;
  SideSections side;
  side.frame = SectionFrame{&grey, std::abs(line.direction.x()) >= std::abs(line.direction.y())};
  side.grid = &grid;
  side.path = &path;
  side.tuning = &tuning;
  side.side = static_cast<int>(index);
  const SectionFrame& frame = side.frame;
  const double a_per_t = frame.a_of(line.direction);  // sections advance along the side (> 0) or against it
  side.cos_t = std::abs(a_per_t);
  side.tan_t = std::abs(frame.b_of(line.direction)) / side.cos_t;
  const double width_px = path.width_px, extent_px = width_px / side.cos_t;  // the rough width, and across a section
  const double first_half_window_px = extent_px / 2 + tuning.window_margin_px + tuning.coarse_window_extra_px;
  const auto mm = [&](double px) { return px / px_per_m * 1e3; };

  // Sections stop short of corners (so that no window or flank reaches the next side) and of free ends.
  const auto corner_stop = [&](double angle, const Point2& at) {
    const double need = (first_half_window_px + tuning.flank_px + width_px / 2 + tuning.corner_clearance_px) /
                        std::max(std::sin(angle), tuning.min_corner_sine);
    const double want = options.metrics.corner_trim_m * px_per_m;
    if (need > want) {
      warnings.push_back(fmt::format("the corner at {} is sharp ({:.0f}°): cross-sections stop {:.2f} mm from it",
                                     position_text(at, px_per_m, options), angle * 180 / std::numbers::pi, mm(need)));
    }
    // Sections run a little closer than the trim to the coarse corner: the metrics trim again at the
    // measured corner, by the same distance as for simulated paths, so the coarse corner's error and a
    // side bending off its line near the corner do not change which part of the side is measured.
    return std::max(need, want - std::max(tuning.corner_approach_cells * tuning.cell_px, tuning.corner_approach_m * px_per_m));
  };
  // A free end's rough position (the extreme coarse cell) is within a cell of the mark's tip.
  const double end_cut = tuning.end_cut_widths * width_px + 0.5 * width_px * side.tan_t + tuning.cell_px + tuning.end_cut_px;
  const double end_reach = 0.5 * width_px * side.tan_t + tuning.window_margin_px + tuning.cell_px + tuning.end_reach_px;
  const double t_start = line.along(coarse.start), t_end = line.along(coarse.end);
  const double body_from = t_start + (coarse.start_is_corner ? corner_stop(coarse.start_angle_rad, coarse.start) : end_cut);
  const double body_to = t_end - (coarse.end_is_corner ? corner_stop(coarse.end_angle_rad, coarse.end) : end_cut);
  if (body_to - body_from < tuning.min_body_px) {
    throw Error(SourceLocation{options.label, 0, 0}, fmt::format("a side is too short to measure ({:.2f} mm)", mm(t_end - t_start)));
  }
  const double a_from = frame.a_of(line.at(body_from)), a_to = frame.a_of(line.at(body_to));
  side.body_first = static_cast<int>(std::ceil(std::min(a_from, a_to) - 0.5));
  side.body_last = static_cast<int>(std::floor(std::max(a_from, a_to) - 0.5));
  // The low-a end is the side's start when the sections advance along it.
  side.low_free = a_per_t > 0 ? !coarse.start_is_corner : !coarse.end_is_corner;
  side.high_free = a_per_t > 0 ? !coarse.end_is_corner : !coarse.start_is_corner;
  const double t_low = a_per_t > 0 ? t_start - end_reach : t_end + end_reach;
  const double t_high = a_per_t > 0 ? t_end + end_reach : t_start - end_reach;
  side.first = side.low_free ? static_cast<int>(std::floor(frame.a_of(line.at(t_low)))) : side.body_first;
  side.last = side.high_free ? static_cast<int>(std::ceil(frame.a_of(line.at(t_high)))) : side.body_last;
  if (side.first < 0 || side.last >= frame.size_a()) {
    throw Error(SourceLocation{options.label, 0, 0}, "the mark's end is too close to the image border to be measured");
  }
  side.end_fit_sections = static_cast<std::size_t>(
      std::max(static_cast<double>(tuning.end_fit_min_sections), tuning.end_fit_m * px_per_m * side.cos_t));
  for (int a = side.first; a <= side.last; ++a) {
    Section s;
    s.a = a;
    s.body = a >= side.body_first && a <= side.body_last;
    side.sections.push_back(s);
  }
  return side;
}

}  // namespace stiffpath::vision::detail
