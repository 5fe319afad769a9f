// A free end of the mark: the path's farthest point from the round laser spot fitted at the tip of its footprint.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "cross_section.hpp"
#include "end_tip.hpp"
#include "stiffpath/core/median.hpp"

namespace stiffpath::vision::detail {

namespace {

// Robust estimates of many sections: the upper middle (one of the values, one partial sort) is enough.
double median(std::vector<double> v) { return core::median(std::move(v), core::MedianRule::upper_middle); }

// The pixel box holding this side's coarse cells at or beyond `seed` along `outward` (from a cell and a
// margin behind it), widened by `margin`.
cv::Rect end_region(const SideSections& side, const Point2& seed, const Point2& outward, double margin) {
  const CoarsePath& path = *side.path;
  const int cell = side.grid->cell;
  const double from = seed.dot(outward) - side.tuning->tip_box_margin_px - cell;
  double x0 = seed.x(), x1 = seed.x(), y0 = seed.y(), y1 = seed.y();
  for (int gy = path.box.y; gy < path.box.y + path.box.height; ++gy) {
    for (int gx = path.box.x; gx < path.box.x + path.box.width; ++gx) {
      if (path.owner_at(gx, gy) != side.side) continue;
      const Point2 c{(gx + 0.5) * cell, (gy + 0.5) * cell};
      if (c.dot(outward) < from) continue;
      x0 = std::min(x0, c.x()), x1 = std::max(x1, c.x()), y0 = std::min(y0, c.y()), y1 = std::max(y1, c.y());
    }
  }
  const double pad = margin + cell;
  return {cv::Point(static_cast<int>(std::floor(x0 - pad)), static_cast<int>(std::floor(y0 - pad))),
          cv::Point(static_cast<int>(std::ceil(x1 + pad)), static_cast<int>(std::ceil(y1 + pad)))};
}

}  // namespace

Paper section_paper(const SideSections& side, const Section& s) {
  if (!s.lo && !s.hi) {
    const CoarseGrid* grid = side.grid;
    const SectionFrame fr = side.frame;
    const int a = s.a;
    return [grid, fr, a](double b) {
      const Point2 p = fr.xy(a + 0.5, b);
      return grid->paper_at(p.x(), p.y());
    };
  }
  const double lo = s.lo.value_or(*s.hi), hi = s.hi.value_or(*s.lo);
  const double p0 = s.lo_pos, span = s.hi_pos - s.lo_pos;
  return [lo, hi, p0, span](double b) { return std::max(1e-6, lo + (hi - lo) * (b - p0) / span); };
}

evaluation::Line2 end_line(const SideSections& side, bool low, std::size_t count) {
  std::vector<Point2> pts;
  for (int k = 0; k <= side.body_last - side.body_first && pts.size() < count; ++k) {
    const Section& s = side.at(low ? side.body_first + k : side.body_last - k);
    if (s.body && !s.rejected) pts.push_back(side.frame.xy(s.a + 0.5, s.centre));
  }
  return evaluation::fit_line_tls(pts).line;
}

// The end point of the path is where the path reaches farthest along the side, and the footprint of a
// round spot of diameter w reaches exactly w/2 farther: its extent along u is max over the path of
// p·u + w/2, whatever the path does near its end (stops, curves sideways, overshoots and turns back).
// Near that extreme the footprint's edge is a circle of radius R ≥ w/2 (w/2 where the spot stops or
// turns back sharply), so a blurred disk fitted to the outermost part of the edge gives the extent
// c·u + R, and the path's extreme point is c + (R − w/2)·u. The fit's residual and R tell whether
// the end looks like a round spot at all (a square cut gives a flat front: R ≫ w/2 and misfit corners).
FreeEnd measure_free_end(const SideSections& side, const evaluation::Line2& side_line, bool low) {
  const SectionFrame& fr = side.frame;
  const ScanTuning& tuning = *side.tuning;
  // Width and darkness of the mark's last stretch before the end (both from the same darkness scale).
  // A section cuts the band at the band's own local angle, which near a wiggling end is not the side's:
  // its darkness integral is k·w/cos θ with tan θ the local slope of the centre line.
  std::vector<double> ml, kl;
  int seed_a = low ? side.body_first : side.body_last;
  bool seeded = false;
  for (int k = 0; k <= side.body_last - side.body_first && ml.size() < side.end_fit_sections; ++k) {
    const int a = low ? side.body_first + k : side.body_last - k;
    const Section& s = side.at(a);
    if (!s.body || s.rejected) continue;
    ml.push_back(s.mass / std::hypot(1.0, local_slope(side, a))), kl.push_back(s.core);
    if (!seeded) seed_a = a, seeded = true;
  }
  const double core = median(kl), k_local = core / side.core_factor, w = median(ml) / k_local;
  const double sigma = std::sqrt(side.blur_px * side.blur_px + 1.0 / 12);  // blur and the pixels' own area
  const double dir = low ? -1.0 : 1.0;  // outward along a
  const Point2 outward = side_line.direction * (fr.a_of(side_line.direction) * dir > 0 ? 1.0 : -1.0);

  // The search box: every cell of this side at or beyond the seed along u, widened by the mark's width
  // and the blur, so a hook or a wiggle of any size is inside it.
  TipSearch search;
  search.seed = fr.xy(seed_a + 0.5, side.at(seed_a).centre);
  search.outward = outward;
  search.threshold = tuning.tip_threshold_ratio * core;
  search.seed_reach_px = w / 2;
  search.box = end_region(side, search.seed, outward, w + tuning.window_margin_px + tuning.tip_box_margin_px);
  FreeEnd result;
  const std::optional<TipExtreme> far = farthest_dark_point(*fr.grey, *side.grid, search);
  if (!far) {
    // Nothing dark where the last section was measured: the end is somewhere between that section and the
    // far side of the search box (the side's own cells beyond it, widened), no farther.
    result.cap = search.seed;
    result.round = false;
    double reach = 0;
    const cv::Rect& b = search.box;
    for (const Point2& corner : {Point2(b.x, b.y), Point2(b.x + b.width, b.y), Point2(b.x, b.y + b.height), Point2(b.x + b.width, b.y + b.height)}) {
      reach = std::max(reach, (corner - search.seed).dot(outward));
    }
    result.uncertainty_px = reach;
    return result;
  }
  result.continues = far->at_box_edge;
  TipGuess guess;
  guess.radius = w / 2;
  guess.centre = far->point - outward * (guess.radius - 0.5);
  guess.outward = outward;
  guess.darkness = k_local;
  guess.sigma = sigma;
  guess.half_angle_rad = tuning.tip_half_angle_deg * std::numbers::pi / 180;
  const TipFit fit = fit_end_tip(*fr.grey, *side.grid, guess);
  result.radius = fit.radius;
  result.rms = fit.rms;
  // A tip sharper than the spot cannot be drawn by it; a much blunter one is a cut, or a dot burnt larger
  // than the spot, whose centre is ambiguous by R − w/2. A square cut also misfits at its corners.
  result.round = fit.converged && fit.rms < tuning.round_tip_max_rms && fit.radius > tuning.round_tip_min_radius * (w / 2) &&
                 fit.radius < tuning.round_tip_max_radius * (w / 2);
  // The footprint's extent along u from the fit, or from the farthest dark pixel (its centre is within
  // about a pixel of the edge at half darkness) when the fit strays from it.
  const double pixel_extent = far->point.dot(outward) + 0.5;
  double extent = fit.centre.dot(outward) + fit.radius;
  if (!fit.converged || std::abs(extent - pixel_extent) > w / 2) extent = pixel_extent;
  const Point2 across = fit.converged ? fit.centre - outward * fit.centre.dot(outward) : far->point - outward * far->point.dot(outward);
  result.cap = across + outward * (extent - w / 2);
  // Drawn by a round spot of diameter w, the path reaches exactly w/2 short of the footprint's extent;
  // a dot burnt larger than the spot (radius R) has its centre up to R − w/2 farther in, and an end
  // cut or smeared otherwise is known to about half the width (and a pixel, for the edge's position).
  if (!result.round) result.uncertainty_px = std::max(w / 2 + 1.0, fit.converged ? fit.radius - w / 2 : 0.0);
  return result;
}

}  // namespace stiffpath::vision::detail
