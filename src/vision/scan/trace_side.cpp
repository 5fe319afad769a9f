// Sub-pixel centre line and width of one side from intensity-weighted cross-sections along the nearer image axis.
#include <algorithm>
#include <fmt/format.h>

#include "side_trace.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/median.hpp"

namespace stiffpath::vision::detail {

namespace {

// The accepted body sections' centres and widths, and the side's median width.
void collect_centres(const SideSections& side, SideTrace& out, const ScanOptions& options) {
  for (const auto& s : side.sections) {
    if (!s.body || s.rejected) continue;
    out.centres.push_back(side.frame.xy(s.a + 0.5, s.centre));
    out.widths.push_back(s.width);
  }
  if (out.centres.size() < options.tuning.min_sections) {
    throw Error(SourceLocation{options.label, 0, 0}, "too few usable cross-sections on a side of the mark");
  }
  out.width = core::median(out.widths, core::MedianRule::upper_middle);
  out.darkness = side.darkness;
}

// The side's free ends: the path's end points (round-spot cap centres) and, for ends that are not round,
// a warning with the bound on their position along the side.
void measure_free_ends(const SideSections& side, bool advancing, SideTrace& out, double px_per_m, const ScanOptions& options) {
  const auto mm = [&](double px) { return px / px_per_m * 1e3; };
  const evaluation::Line2 body_line = evaluation::fit_line_tls(out.centres).line;
  for (const bool low : {true, false}) {
    if (!(low ? side.low_free : side.high_free)) continue;
    const FreeEnd end = measure_free_end(side, body_line, low);
    (advancing == low ? out.start_cap : out.end_cap) = end.cap;
    if (end.continues) {
      throw Error(SourceLocation{options.label, 0, 0},
                  fmt::format("the mark goes on past the end of a side near {}, so that end cannot be measured: it is not "
                              "a free end (a corner that was not found, or a mark with more sides than asked for)",
                              position_text(end.cap, px_per_m, options)));
    }
    if (!end.round) {
      out.end_uncertainty += end.uncertainty_px;
      out.warnings.push_back(fmt::format("the mark's end near {} is not a round laser-spot end (tip radius {:.3f} mm for a "
                                         "{:.3f} mm wide mark); its position along the side may be off by up to {:.3f} mm",
                                         position_text(end.cap, px_per_m, options), mm(end.radius), mm(out.width),
                                         mm(end.uncertainty_px)));
    }
  }
}

}  // namespace

SideTrace trace_side(const cv::Mat& grey, const CoarseGrid& grid, const CoarsePath& path, std::size_t index, double px_per_m,
                     const ScanOptions& options) {
  const ScanTuning& tuning = options.tuning;
  const CoarseSide& coarse = path.sides[index];
  const evaluation::Line2& line = coarse.line;
  SideTrace out;
  SideSections side = lay_out_sections(grey, grid, path, index, px_per_m, options, out.warnings);
  const bool advancing = side.frame.a_of(line.direction) > 0;  // sections run from the side's start to its end

  // Pass 1 on the coarse paper level gives the mark's extent across a section, hence the windows.
  const double coarse_extent_px = path.width_px / side.cos_t;
  const RoughProfile rough = centre_roughly(side, line, coarse_extent_px,
                                            coarse_extent_px / 2 + tuning.window_margin_px + tuning.coarse_window_extra_px, options);
  side.window_half_px = rough.extent_px / 2 + tuning.window_margin_px;
  const double centroid_half_window_px = rough.extent_px / 2 + tuning.centroid_margin_px;
  if (path.sides.size() > 1) {
    drop_crowded_sections(side, coarse, side.window_half_px + tuning.flank_px, rough.core_darkness * tuning.crowding_darkness_ratio,
                          px_per_m, options);
    if (side.crowded_elsewhere > 0) {
      out.warnings.push_back(fmt::format("{} cross-sections of a side were left out where another side of the mark comes within "
                                         "their reach away from the corners (the path crosses or touches itself)",
                                         side.crowded_elsewhere));
    }
  }

  // Paper levels from both flanks (the end sections' centred on their own end's local line), then pass 2.
  measure_paper_levels(side, side.low_free ? end_line(side, true, side.end_fit_sections) : line,
                       side.high_free ? end_line(side, false, side.end_fit_sections) : line);
  if (measure_sections(side, centroid_half_window_px)) {
    out.warnings.push_back("the mark comes so close to the image border that some cross-sections are cut short");
  }

  out.rejected = reject_outliers(side, line);
  out.sections = static_cast<std::size_t>(side.body_last - side.body_first + 1);
  collect_centres(side, out, options);
  measure_free_ends(side, advancing, out, px_per_m, options);
  if (!advancing) std::reverse(out.centres.begin(), out.centres.end()), std::reverse(out.widths.begin(), out.widths.end());
  return out;
}

}  // namespace stiffpath::vision::detail
