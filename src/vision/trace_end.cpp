// A free end of the mark: the path's farthest point from the round laser spot fitted at the tip of its footprint.
#include <algorithm>
#include <cmath>

#include "cross_section.hpp"
#include "end_tip.hpp"

namespace stiffpath::vision::detail {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

double b_on(const SectionFrame& fr, const evaluation::Line2& l, double a) {
  return fr.b_of(l.at((a - fr.a_of(l.origin)) / fr.a_of(l.direction)));
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
    if (!s.rejected) pts.push_back(side.frame.xy(s.a + 0.5, s.centre));
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
FreeEnd measure_free_end(const SideSections& side, const evaluation::Line2& side_line, bool low, const ScanOptions& options) {
  const SectionFrame& fr = side.frame;
  const evaluation::Line2 l = end_line(side, low, side.end_fit);
  // Width and darkness of the mark's last stretch before the end (both from the same darkness scale).
  std::vector<double> ml, kl;
  int seed_a = low ? side.body_first : side.body_last;
  bool seeded = false;
  for (int k = 0; k <= side.body_last - side.body_first && ml.size() < side.end_fit; ++k) {
    const int a = low ? side.body_first + k : side.body_last - k;
    const Section& s = side.at(a);
    if (s.rejected) continue;
    ml.push_back(s.mass), kl.push_back(s.core);
    if (!seeded) seed_a = a, seeded = true;
  }
  const double core = median(kl), k_local = core / side.core_factor, w = median(ml) / k_local * side.cos_t;
  const double sigma = std::sqrt(side.blur_px * side.blur_px + 1.0 / 12);  // blur and the pixels' own area
  const double dir = low ? -1.0 : 1.0;  // outward along a
  const Point2 outward = side_line.direction * (fr.a_of(side_line.direction) * dir > 0 ? 1.0 : -1.0);

  // The search box: from the last body section out to the last section, wide enough for a hook.
  const double reach = side.h_wide + 2 * w + options.band_margin_px;
  const int a_in = low ? seed_a + 2 : seed_a - 2, a_out = low ? side.first - 2 : side.last + 2;
  double b_lo = 1e300, b_hi = -1e300;
  for (const int a : {a_in, a_out}) b_lo = std::min(b_lo, b_on(fr, l, a + 0.5) - reach), b_hi = std::max(b_hi, b_on(fr, l, a + 0.5) + reach);
  const Point2 p0 = fr.xy(std::min(a_in, a_out), b_lo), p1 = fr.xy(std::max(a_in, a_out) + 1, b_hi);
  TipSearch search;
  search.box = cv::Rect(cv::Point(static_cast<int>(std::floor(std::min(p0.x(), p1.x()))), static_cast<int>(std::floor(std::min(p0.y(), p1.y())))),
                        cv::Point(static_cast<int>(std::ceil(std::max(p0.x(), p1.x()))), static_cast<int>(std::ceil(std::max(p0.y(), p1.y())))));
  search.seed = fr.xy(seed_a + 0.5, side.at(seed_a).centre);
  search.outward = outward;
  search.threshold = 0.5 * core;
  FreeEnd result;
  const std::optional<Point2> far = farthest_dark_point(*fr.grey, *side.grid, search);
  if (!far) {
    result.cap = search.seed;
    result.round = false;
    return result;
  }
  TipGuess guess;
  guess.radius = w / 2;
  guess.centre = *far - outward * (guess.radius - 0.5);
  guess.outward = outward;
  guess.darkness = k_local;
  guess.sigma = sigma;
  const TipFit fit = fit_end_tip(*fr.grey, *side.grid, guess);
  result.radius = fit.radius;
  result.rms = fit.rms;
  result.cap = fit.centre + outward * (fit.radius - w / 2);
  // A tip sharper than the spot cannot be drawn by it; a much blunter one is a cut, or a dot burnt larger
  // than the spot, whose centre is ambiguous by R − w/2. A square cut also misfits at its corners.
  result.round = fit.converged && fit.rms < 0.06 && fit.radius > 0.75 * (w / 2) && fit.radius < 1.5 * (w / 2);
  return result;
}

}  // namespace stiffpath::vision::detail
