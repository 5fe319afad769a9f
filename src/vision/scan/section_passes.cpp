// The passes over a side's sections: rough centres, paper levels from the flanks, centroids and integrals, the mark's darkness and blur.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "side_trace.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/median.hpp"

namespace stiffpath::vision::detail {

namespace {

// Robust estimates of many sections: the upper middle (one of the values, one partial sort) is enough.
double median(std::vector<double> v) { return core::median(std::move(v), core::MedianRule::upper_middle); }

// Darkness-weighted centre of the side's own coarse cells in the cell column of section a (b if none).
double coarse_guess(const SideSections& side, int a, double b) {
  const CoarseGrid& grid = *side.grid;
  const CoarsePath& path = *side.path;
  const int cell = grid.cell, ga = (a * 2 + 1) / (2 * cell);
  const bool columns = side.frame.columns;
  const cv::Rect& box = path.box;
  double sw = 0, sb = 0;
  for (int gb = columns ? box.y : box.x; gb < (columns ? box.y + box.height : box.x + box.width); ++gb) {
    const int row = columns ? gb : ga, col = columns ? ga : gb;
    if (path.owner_at(col, row) != side.side) continue;
    const double w = grid.darkness.at<float>(row, col);
    sw += w;
    sb += w * (gb + 0.5) * cell;
  }
  return sw > 0 ? sb / sw : b;
}

}  // namespace

RoughProfile centre_roughly(SideSections& side, const evaluation::Line2& line, double coarse_extent_px,
                            double rough_half_window_px, const ScanOptions& options) {
  const ScanTuning& tuning = *side.tuning;
  const SectionFrame& frame = side.frame;
  std::vector<double> masses, cores;
  for (Section& s : side.sections) {
    if (!s.body) continue;
    const Paper paper = section_paper(side, s);  // the coarse grid's: the flanks are not measured yet
    const int a = s.a;
    double c = coarse_guess(side, a, across_on_line(frame, line, a + 0.5));
    c = centred_sums(frame, a, c, coarse_extent_px / 2 + tuning.rough_window_px, paper).centroid(c);
    for (int it = 0; it < tuning.rough_refinements; ++it) {
      c = centred_sums(frame, a, c, coarse_extent_px / 2 + tuning.rough_refine_px, paper).centroid(c);
    }
    s.centre = c;
    masses.push_back(centred_sums(frame, a, c, rough_half_window_px, paper).mass);
    cores.push_back(core_darkness(frame, a, c, paper));
  }
  RoughProfile rough;
  rough.core_darkness = median(cores);
  if (!(rough.core_darkness > tuning.min_mark_darkness)) {
    throw Error(SourceLocation{options.label, 0, 0}, fmt::format("the mark is too faint to measure (darkness {:.3f})", rough.core_darkness));
  }
  rough.extent_px = median(masses) / rough.core_darkness;
  return rough;
}

void measure_paper_levels(SideSections& side, const evaluation::Line2& low_line, const evaluation::Line2& high_line) {
  const ScanTuning& tuning = *side.tuning;
  const SectionFrame& frame = side.frame;
  const int flank = tuning.flank_px;
  std::vector<std::optional<double>> low_flank(side.sections.size()), high_flank(side.sections.size());
  for (std::size_t i = 0; i < side.sections.size(); ++i) {
    Section& s = side.sections[i];
    if (s.crowded) continue;
    if (!s.body) s.centre = across_on_line(frame, s.a < side.body_first ? low_line : high_line, s.a + 0.5);
    const int low_end = static_cast<int>(std::floor(s.centre - side.window_half_px));
    const int high_start = static_cast<int>(std::floor(s.centre + side.window_half_px)) + 1;
    low_flank[i] = flank_median(frame, s.a, low_end - flank, low_end);
    high_flank[i] = flank_median(frame, s.a, high_start, high_start + flank);
    s.lo_pos = low_end - flank / 2.0;
    s.hi_pos = high_start + flank / 2.0;
  }
  low_flank = running_mean(low_flank, tuning.paper_window_sections / 2);
  high_flank = running_mean(high_flank, tuning.paper_window_sections / 2);
  for (std::size_t i = 0; i < side.sections.size(); ++i) {
    side.sections[i].lo = low_flank[i];
    side.sections[i].hi = high_flank[i];
  }
}

bool measure_sections(SideSections& side, double centroid_half_window_px) {
  const ScanTuning& tuning = *side.tuning;
  const SectionFrame& frame = side.frame;
  std::vector<double> cores, spreads, masses;
  bool clipped = false;
  for (Section& s : side.sections) {
    if (!s.body) continue;
    const Paper paper = section_paper(side, s);
    for (int it = 0; it < tuning.centroid_iterations; ++it) {
      s.centre = centred_sums(frame, s.a, s.centre, centroid_half_window_px, paper).centroid(s.centre);
    }
    s.core = core_darkness(frame, s.a, s.centre, paper);
    const WindowSums wide = centred_sums(frame, s.a, s.centre, side.window_half_px, paper);
    s.mass = wide.mass;
    spreads.push_back(wide.variance());
    cores.push_back(s.core);
    masses.push_back(s.mass);
    clipped = clipped || wide.clipped;
  }
  // The core of a mark only a few blur widths wide does not reach full darkness: a box of section extent
  // S blurred by σ (profile variance S²/12 + σ², + 1/12 for the pixel sampling) peaks at
  // k·erf(S / (2√2·√(σ² + 1/12))). Solve for the full darkness k, S and σ together.
  const double core = median(cores), mass = median(masses), spread = median(spreads);
  double k = core, sigma = 0;
  for (int it = 0; it < tuning.blur_solve_iterations; ++it) {
    const double extent = mass / k;
    sigma = std::sqrt(std::max(tuning.min_blur_variance_px2, spread - (extent * extent + 1) / 12));
    k = core / std::max(tuning.min_core_erf, std::erf(extent / (2 * std::sqrt(2 * (sigma * sigma + 1.0 / 12)))));
  }
  side.darkness = k;
  side.core_factor = core / k;
  side.blur_px = side.cos_t * sigma;
  // A section crosses the band at the band's local angle θ (tan θ = the centre line's slope db/da), so its
  // darkness integral is k·w/cos θ: for a straight side θ is the side's angle, along a wiggle it varies.
  for (Section& s : side.sections) {
    if (s.body) s.width = s.mass / side.darkness / std::hypot(1.0, local_slope(side, s.a));
  }
  return clipped;
}

}  // namespace stiffpath::vision::detail
