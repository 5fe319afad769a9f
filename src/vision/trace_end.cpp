// A free end of the mark: the path's end from the darkness area beyond a cut across the mark (round laser spot).
#include <algorithm>
#include <cmath>
#include <tuple>
#include <numbers>

#include "cross_section.hpp"

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

// The interval of b where the line a = const crosses the capsule of radius r around segment p–q (all in
// the section frame's (a, b)); empty (lo > hi) when it misses. The capsule is convex, so the chord is
// the union of the chords of its two end disks and of its straight part.
std::pair<double, double> capsule_chord(double a, Point2 p, Point2 q, double r) {
  double lo = 1e300, hi = -1e300;
  for (const Point2& c : {p, q}) {
    const double dx = a - c.x();
    if (std::abs(dx) <= r) {
      const double h = std::sqrt(r * r - dx * dx);
      lo = std::min(lo, c.y() - h), hi = std::max(hi, c.y() + h);
    }
  }
  const Point2 d = q - p;
  const double len = d.norm();
  if (len > 0 && std::abs(d.x()) > 1e-12) {
    const Point2 u = d / len;  // |offset| = |(a − p.x)·u.y − (b − p.y)·u.x| ≤ r, and 0 ≤ (x − p)·u ≤ len
    const double centre = p.y() + (a - p.x()) * u.y() / u.x(), half = r / std::abs(u.x());
    double s_lo = centre - half, s_hi = centre + half;
    if (std::abs(u.y()) > 1e-12) {
      const double t0 = (p.y() + (0 - (a - p.x()) * u.x()) / u.y()), t1 = (p.y() + (len - (a - p.x()) * u.x()) / u.y());
      s_lo = std::max(s_lo, std::min(t0, t1)), s_hi = std::min(s_hi, std::max(t0, t1));
    } else if ((a - p.x()) * u.x() < 0 || (a - p.x()) * u.x() > len) {
      s_lo = 1e300, s_hi = -1e300;
    }
    if (s_lo <= s_hi) lo = std::min(lo, s_lo), hi = std::max(hi, s_hi);
  }
  return {lo, hi};
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

// The darkness area beyond the cut edge a_cut is w·|end − Q| + πw²/8 for a round spot of diameter w,
// Q being where the path crosses the cut (blur moves no darkness across a cut through the uniform
// band). First with full windows; then, to keep paper texture out, with windows covering only the
// expected footprint (the path's last stretch widened by w/2 + 3σ_blur + ½ px) and a cut moved up to
// (w/2)·tan θ + 3σ + ½ px before the end.
FreeEnd measure_free_end(const SideSections& side, bool low, const ScanOptions& options) {
  const SectionFrame& fr = side.frame;
  const evaluation::Line2 l = end_line(side, low, side.end_fit);
  // Width and darkness of the mark's last stretch before the end (both from the same darkness scale).
  std::vector<double> ml, kl;
  for (int k = 0; k <= side.body_last - side.body_first && ml.size() < side.end_fit; ++k) {
    const Section& s = side.at(low ? side.body_first + k : side.body_last - k);
    if (!s.rejected) ml.push_back(s.mass), kl.push_back(s.core);
  }
  const double k_local = median(kl) / side.core_factor, w = median(ml) / k_local * side.cos_t;
  // Edge spread: the blur and the pixels' own area (variance 1/12).
  const double sigma = std::sqrt(side.blur_px * side.blur_px + 1.0 / 12);
  const double margin = std::min(1.5 * sigma + 0.25, options.band_margin_px);
  // Darkness of a blurred edge beyond a window `margin` outside it, per unit edge length (Gaussian blur):
  // σ·(φ(z) − z·(1 − Φ(z))), z = margin/σ. Added back for the footprint's edges.
  const double z = margin / sigma;
  const double tail = sigma * (std::exp(-0.5 * z * z) / std::sqrt(2 * std::numbers::pi) - z * 0.5 * std::erfc(z / std::sqrt(2.0)));
  const double radius = w / 2 + margin;
  const double dir = low ? -1.0 : 1.0;  // outward along a
  const Point2 outward = l.direction * (fr.a_of(l.direction) * dir > 0 ? 1.0 : -1.0);
  const double slope_a = std::abs(fr.a_of(l.direction));
  int a_cut = low ? side.body_first : side.body_last + 1;
  std::optional<Point2> cap;
  FreeEnd result;
  for (int pass = 0; pass < 3; ++pass) {
    if (cap) {
      // Move the cut towards the end, but keep it on the full-width band.
      const double keep = (w / 2) * side.tan_t + 3 * sigma + 0.5;
      const double a_limit = fr.a_of(*cap) - dir * keep * slope_a;
      const int candidate = low ? static_cast<int>(std::ceil(a_limit)) : static_cast<int>(std::floor(a_limit));
      a_cut = low ? std::clamp(candidate, side.first + 1, side.body_first) : std::clamp(candidate, side.body_last + 1, side.last);
    }
    const Point2 q = l.at((a_cut - fr.a_of(l.origin)) / fr.a_of(l.direction));
    const Point2 inner = q - outward * (2 * radius);
    double area = 0;
    std::vector<std::pair<Point2, double>> profile;  // centre-line point of each section and its relative darkness
    for (int a = low ? a_cut - 1 : a_cut; a >= side.first && a <= side.last; a += low ? -1 : 1) {
      const double b_mid = b_on(fr, l, a + 0.5);
      double from = b_mid - side.h_wide, to = b_mid + side.h_wide;
      if (cap) {  // the b-range of section a within `radius` of the segment from inside the band to the cap
        const Point2 p{fr.a_of(inner), fr.b_of(inner)}, e{fr.a_of(*cap), fr.b_of(*cap)};
        std::tie(from, to) = capsule_chord(a + 0.5, p, e, radius);
        if (from > to) break;
      }
      const double m = window_sums(fr, a, from, to, section_paper(side, side.at(a))).mass / k_local;
      const double level = m * side.cos_t / w;
      profile.emplace_back(fr.xy(a + 0.5, b_mid), level);
      area += m;
    }
    if (cap) area += tail * (std::numbers::pi * w / 2 + 2 * std::max(0.0, (*cap - q).dot(outward)));
    cap = q + outward * ((area - std::numbers::pi * w * w / 8) / w);
    // A round spot's profile falls to half at 0.433·w beyond its centre (√3/2 · w/2).
    // Shape check: each section's darkness against a round spot's chord through that section (the
    // capsule of radius w/2 ending at the cap), blurred along the section axis by σ.
    const Point2 p0{fr.a_of(inner), fr.b_of(inner)}, p1{fr.a_of(*cap), fr.b_of(*cap)};
    double sq = 0, norm = 0;
    int count = 0;
    for (int k = -4; k <= 4; ++k) norm += std::exp(-0.125 * k * k);
    for (const auto& [point, level] : profile) {
      const double tau = (point - *cap).dot(outward);
      if (tau < -0.25 * w || tau > 0.5 * w + 2 * sigma) continue;
      double expected = 0;
      for (int k = -4; k <= 4; ++k) {  // 9-point Gaussian quadrature on ±2σ
        const auto [from, to] = capsule_chord(fr.a_of(point) + 0.5 * k * sigma, p0, p1, w / 2);
        expected += std::exp(-0.125 * k * k) * std::max(0.0, to - from) * side.cos_t / w;
      }
      sq += std::pow(level - expected / norm, 2);
      ++count;
    }
    result.round = count > 0 && std::sqrt(sq / count) < 0.06;
  }
  result.cap = *cap;
  return result;
}

}  // namespace stiffpath::vision::detail
