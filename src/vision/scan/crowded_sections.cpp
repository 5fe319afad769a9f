// Cross-sections near a corner that reach the other side of the mark: left out, or the corner refused beyond the trim.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "cross_section.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision::detail {

void drop_crowded_sections(SideSections& side, const CoarseSide& coarse, double reach_px, double dark, double px_per_m,
                           const ScanOptions& o) {
  const CoarsePath& path = *side.path;
  const int cell = side.grid->cell;
  const SectionFrame& frame = side.frame;
  const evaluation::Line2& line = coarse.line;
  const double t_start = line.along(coarse.start), t_end = line.along(coarse.end);
  std::vector<double> from_start, from_end;  // distances of crowded sections from the start / end corner (px)
  double first_t = 1e300, last_t = -1e300;   // extent of the body along the line
  for (auto& s : side.sections) {
    if (!s.body) continue;
    const double t = line.along(frame.xy(s.a + 0.5, s.centre));
    first_t = std::min(first_t, t), last_t = std::max(last_t, t);
    // A pixel within reach, dark (a third of the mark's darkness), in a cell another side owns.
    const int ga = (2 * s.a + 1) / (2 * cell);
    const int b0 = std::max(0, static_cast<int>(std::floor(s.centre - reach_px)));
    const int b1 = std::min(frame.size_b() - 1, static_cast<int>(std::floor(s.centre + reach_px)));
    for (int b = b0; b <= b1 && !s.crowded; ++b) {
      const int owner = frame.columns ? path.owner_at(ga, b / cell) : path.owner_at(b / cell, ga);
      if (owner == kNoSide || owner == side.side) continue;
      const Point2 p = frame.xy(s.a + 0.5, b + 0.5);
      s.crowded = 1.0 - frame.at(s.a, b) / side.grid->paper_at(p.x(), p.y()) > dark;
    }
    if (!s.crowded) continue;
    s.body = false;
    from_start.push_back(t - t_start);
    from_end.push_back(t_end - t);
  }
  // The run of crowded sections that starts where the sections start next to a corner: how far from the
  // corner the other side stays within reach. (Crowded sections elsewhere, where the path crosses or
  // touches itself, are only left out.)
  const double gap = side.tuning->crowded_run_gap_cells * cell;
  const auto run_from = [&](std::vector<double> d, double first) {
    std::sort(d.begin(), d.end());
    double reach = first;
    for (const double x : d) {
      if (x > reach + gap) break;
      reach = std::max(reach, x);
    }
    return reach > first ? reach : 0.0;
  };
  const double start_reach = coarse.start_is_corner ? run_from(from_start, first_t - t_start) : 0.0;
  const double end_reach = coarse.end_is_corner ? run_from(from_end, t_end - last_t) : 0.0;
  for (std::size_t i = 0; i < from_start.size(); ++i) {
    if (!(from_start[i] <= start_reach) && !(from_end[i] <= end_reach)) ++side.crowded_elsewhere;
  }
  const double trim = o.metrics.corner_trim_m * px_per_m;
  for (const auto& [reach, at] : {std::pair{start_reach, coarse.start}, std::pair{end_reach, coarse.end}}) {
    if (reach <= trim) continue;
    const double need_mm = std::ceil((reach + gap) / px_per_m * 1e4) / 10;
    throw Error(SourceLocation{o.label, 0, 0},
                fmt::format("at the corner near {} the two sides run so close together that a side can "
                            "only be measured from {:.2f} mm of the corner on, farther than the {:.2f} mm corner trim: the "
                            "number would not be the side's; measure with a corner trim of at least {:.1f} mm "
                            "(--corner-trim-mm)", position_text(at, px_per_m, o), reach / px_per_m * 1e3,
                            o.metrics.corner_trim_m * 1e3, need_mm));
  }
  // The body's first and last sections must still be body sections for the free-end and slope code.
  while (side.body_first < side.body_last && !side.at(side.body_first).body) ++side.body_first;
  while (side.body_last > side.body_first && !side.at(side.body_last).body) --side.body_last;
}

}  // namespace stiffpath::vision::detail
