// Sub-pixel centre line and width of one side from intensity-weighted cross-sections along the nearer image axis.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "cross_section.hpp"
#include "scan_internal.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/median.hpp"

namespace stiffpath::vision::detail {

namespace {

using evaluation::Line2;

// Robust estimates of many sections: the upper middle (one of the values, one partial sort) is enough.
double median(std::vector<double> v) { return core::median(std::move(v), core::MedianRule::upper_middle); }

double b_on(const SectionFrame& fr, const Line2& l, double a) {
  return fr.b_of(l.at((a - fr.a_of(l.origin)) / fr.a_of(l.direction)));
}

// Darkness-weighted centre of the side's own coarse cells in the cell column of section a (b if none).
double coarse_guess(const SideSections& side, const CoarsePath& path, int k, int a, double b) {
  const CoarseGrid& grid = *side.grid;
  const int cell = grid.cell, ga = (a * 2 + 1) / (2 * cell);
  const bool columns = side.frame.columns;
  const cv::Rect& box = path.box;
  double sw = 0, sb = 0;
  for (int gb = columns ? box.y : box.x; gb < (columns ? box.y + box.height : box.x + box.width); ++gb) {
    const int row = columns ? gb : ga, col = columns ? ga : gb;
    if (path.owner_at(col, row) != k) continue;
    const double w = grid.darkness.at<float>(row, col);
    sw += w;
    sb += w * (gb + 0.5) * cell;
  }
  return sw > 0 ? sb / sw : b;
}

// Flags sections whose width is far from the median (dust on the mark, gaps) or whose centre, measured
// from the side's line, is off its neighbours' (their median, carried to the section along the median
// slope of the offsets, so that a side bending near its end, where the neighbours are all on one side,
// is not taken for an outlier).
std::size_t reject_outliers(SideSections& side, const Line2& line) {
  std::vector<Section*> body;
  for (auto& s : side.secs) if (s.body) body.push_back(&s);
  std::vector<double> widths, dev, resid(body.size());
  for (const auto* s : body) widths.push_back(s->width);
  const double w_med = median(widths);
  for (const double w : widths) dev.push_back(std::abs(w - w_med));
  const double w_tol = std::max(0.15 * w_med, 6 * 1.4826 * median(dev));
  std::vector<double> offset(body.size());
  for (std::size_t j = 0; j < body.size(); ++j) offset[j] = body[j]->centre - b_on(side.frame, line, body[j]->a + 0.5);
  for (std::size_t k = 0; k < body.size(); ++k) {
    const std::size_t lo = k >= 10 ? k - 10 : 0, hi = std::min(body.size(), k + 11);
    std::vector<double> near, slopes;
    for (std::size_t j = lo; j + 1 < hi; ++j) slopes.push_back((offset[j + 1] - offset[j]) / (body[j + 1]->a - body[j]->a));
    const double slope = median(slopes);
    for (std::size_t j = lo; j < hi; ++j) near.push_back(offset[j] - slope * (body[j]->a - body[k]->a));
    resid[k] = std::abs(offset[k] - median(near));
  }
  const double c_tol = std::max(0.5, 6 * 1.4826 * median(resid));
  std::size_t rejected = 0;
  for (std::size_t k = 0; k < body.size(); ++k) {
    body[k]->rejected = std::abs(body[k]->width - w_med) > w_tol || resid[k] > c_tol;
    rejected += body[k]->rejected ? 1 : 0;
  }
  return rejected;
}

}  // namespace

SideTrace trace_side(const cv::Mat& grey, const CoarseGrid& grid, const CoarsePath& path, std::size_t index, double px_per_m,
                     const ScanOptions& o) {
  const CoarseSide& side = path.sides[index];
  const SourceLocation where{o.label, 0, 0};
  SideTrace out;
  const Line2& line = side.line;
  SideSections ss;
  ss.frame = SectionFrame{&grey, std::abs(line.direction.x()) >= std::abs(line.direction.y())};
  ss.grid = &grid;
  ss.path = &path;
  ss.side = static_cast<int>(index);
  const SectionFrame& fr = ss.frame;
  const double da = fr.a_of(line.direction);
  ss.cos_t = std::abs(da);
  ss.tan_t = std::abs(fr.b_of(line.direction)) / ss.cos_t;
  const double w0 = path.width_px, s0 = w0 / ss.cos_t, h_wide0 = s0 / 2 + o.band_margin_px + 2;
  const auto to_mm = [&](double px) { return px / px_per_m * 1e3; };

  // Sections stop short of corners (so no window or flank reaches the next side) and of free ends.
  auto corner_trim = [&](double angle, const Point2& at) {
    const double need = (h_wide0 + o.flank_px + w0 / 2 + 4) / std::max(std::sin(angle), 0.1);
    const double want = o.metrics.corner_trim_m * px_per_m;
    if (need > want) {
      out.warnings.push_back(fmt::format("the corner at {} is sharp ({:.0f}°): cross-sections stop "
                                         "{:.2f} mm from it", position_text(at, px_per_m, o), angle * 180 / std::numbers::pi, to_mm(need)));
    }
    // Sections run a little closer than the trim to the coarse corner: the metrics trim again at the
    // measured corner, by the same distance as for simulated paths, so the coarse corner's error and a
    // side bending off its line near the corner do not change which part of the side is measured.
    return std::max(need, want - std::max(3.0 * o.cell_px, 0.15e-3 * px_per_m));
  };
  // A free end's rough position (the extreme coarse cell) is within a cell of the mark's tip.
  const double cut = 0.6 * w0 + 0.5 * w0 * ss.tan_t + o.cell_px + 1.5;
  const double reach_out = 0.5 * w0 * ss.tan_t + o.band_margin_px + o.cell_px + 2;
  const double t_start = line.along(side.start), t_end = line.along(side.end);
  const double t_lo = t_start + (side.start_is_corner ? corner_trim(side.start_angle_rad, side.start) : cut);
  const double t_hi = t_end - (side.end_is_corner ? corner_trim(side.end_angle_rad, side.end) : cut);
  if (t_hi - t_lo < 10.0) throw Error(where, fmt::format("a side is too short to measure ({:.2f} mm)", to_mm(t_end - t_start)));
  const double a1 = fr.a_of(line.at(t_lo)), a2 = fr.a_of(line.at(t_hi));
  ss.body_first = static_cast<int>(std::ceil(std::min(a1, a2) - 0.5));
  ss.body_last = static_cast<int>(std::floor(std::max(a1, a2) - 0.5));
  const bool low_free = da > 0 ? !side.start_is_corner : !side.end_is_corner;  // the low-a end is the start when da > 0
  const bool high_free = da > 0 ? !side.end_is_corner : !side.start_is_corner;
  const double t_low = da > 0 ? t_start - reach_out : t_end + reach_out, t_high = da > 0 ? t_end + reach_out : t_start - reach_out;
  ss.first = low_free ? static_cast<int>(std::floor(fr.a_of(line.at(t_low)))) : ss.body_first;
  ss.last = high_free ? static_cast<int>(std::ceil(fr.a_of(line.at(t_high)))) : ss.body_last;
  if (ss.first < 0 || ss.last >= fr.size_a()) throw Error(where, "the mark's end is too close to the image border to be measured");

  // Pass 1: centres with the coarse paper level, from a guess on the coarse grid.
  std::vector<double> mass1, core1;
  for (int a = ss.first; a <= ss.last; ++a) {
    Section s;
    s.a = a;
    s.body = a >= ss.body_first && a <= ss.body_last;
    ss.secs.push_back(s);
    if (!s.body) continue;
    const Paper paper = section_paper(ss, s);
    double c = coarse_guess(ss, path, static_cast<int>(index), a, b_on(fr, line, a + 0.5));
    c = centred_sums(fr, a, c, s0 / 2 + 3, paper).centroid(c);
    for (int it = 0; it < 2; ++it) c = centred_sums(fr, a, c, s0 / 2 + 2, paper).centroid(c);
    ss.secs.back().centre = c;
    mass1.push_back(centred_sums(fr, a, c, h_wide0, paper).mass);
    core1.push_back(core_darkness(fr, a, c, paper));
  }
  const double k1 = median(core1);
  if (!(k1 > 0.03)) throw Error(where, fmt::format("the mark is too faint to measure (darkness {:.3f})", k1));
  const double extent = median(mass1) / k1;  // the mark's extent along a section (px)
  ss.h_wide = extent / 2 + o.band_margin_px;
  const double h_tight = extent / 2 + 1;
  ss.end_fit = static_cast<std::size_t>(std::max(20.0, 1.5e-3 * px_per_m * ss.cos_t));
  if (path.sides.size() > 1) {
    drop_crowded_sections(ss, side, ss.h_wide + o.flank_px, k1 / 3, px_per_m, o);
    if (ss.crowded_elsewhere > 0) {
      out.warnings.push_back(fmt::format("{} cross-sections of a side were left out where another side of the mark comes within "
                                         "their reach away from the corners (the path crosses or touches itself)", ss.crowded_elsewhere));
    }
  }

  // Paper level from both flanks of each section, averaged along the side.
  const Line2 low_line = low_free ? end_line(ss, true, ss.end_fit) : line;
  const Line2 high_line = high_free ? end_line(ss, false, ss.end_fit) : line;
  std::vector<std::optional<double>> lo(ss.secs.size()), hi(ss.secs.size());
  for (std::size_t i = 0; i < ss.secs.size(); ++i) {
    Section& s = ss.secs[i];
    if (s.crowded) continue;
    if (!s.body) s.centre = b_on(fr, s.a < ss.body_first ? low_line : high_line, s.a + 0.5);
    const int lo_end = static_cast<int>(std::floor(s.centre - ss.h_wide)), hi_start = static_cast<int>(std::floor(s.centre + ss.h_wide)) + 1;
    lo[i] = flank_median(fr, s.a, lo_end - o.flank_px, lo_end);
    hi[i] = flank_median(fr, s.a, hi_start, hi_start + o.flank_px);
    s.lo_pos = lo_end - o.flank_px / 2.0;
    s.hi_pos = hi_start + o.flank_px / 2.0;
  }
  lo = running_mean(lo, o.baseline_window / 2);
  hi = running_mean(hi, o.baseline_window / 2);

  // Pass 2: centroids in a tight window, darkness integrals (widths) and profile spreads (blur) in the wide one.
  std::vector<double> cores, spreads;
  bool clipped = false;
  for (std::size_t i = 0; i < ss.secs.size(); ++i) {
    Section& s = ss.secs[i];
    s.lo = lo[i];
    s.hi = hi[i];
    if (!s.body) continue;
    const Paper paper = section_paper(ss, s);
    for (int it = 0; it < 3; ++it) s.centre = centred_sums(fr, s.a, s.centre, h_tight, paper).centroid(s.centre);
    s.core = core_darkness(fr, s.a, s.centre, paper);
    const WindowSums wide = centred_sums(fr, s.a, s.centre, ss.h_wide, paper);
    s.mass = wide.mass;
    spreads.push_back(wide.variance());
    cores.push_back(s.core);
    clipped = clipped || wide.clipped;
  }
  // The core of a mark only a few blur widths wide does not reach full darkness: a box of section extent
  // S blurred by σ (profile variance S²/12 + σ², + 1/12 for the pixel sampling) peaks at
  // k·erf(S / (2√2·√(σ² + 1/12))). Solve for the full darkness k, S and σ together.
  std::vector<double> masses;
  for (const auto& s : ss.secs) if (s.body) masses.push_back(s.mass);
  const double core = median(cores), mass = median(masses), spread = median(spreads);
  double k = core, sigma_b = 0;
  for (int it = 0; it < 30; ++it) {
    const double extent_b = mass / k;
    sigma_b = std::sqrt(std::max(0.01, spread - (extent_b * extent_b + 1) / 12));
    k = core / std::max(0.2, std::erf(extent_b / (2 * std::sqrt(2 * (sigma_b * sigma_b + 1.0 / 12)))));
  }
  ss.darkness = k;
  ss.core_factor = core / k;
  ss.blur_px = ss.cos_t * sigma_b;
  // A section crosses the band at the band's local angle θ (tan θ = the centre line's slope db/da), so its
  // darkness integral is k·w/cos θ: for a straight side θ is the side's angle, along a wiggle it varies.
  for (auto& s : ss.secs) {
    if (s.body) s.width = s.mass / ss.darkness / std::hypot(1.0, local_slope(ss, s.a));
  }
  if (clipped) out.warnings.push_back("the mark comes so close to the image border that some cross-sections are cut short");

  out.rejected = reject_outliers(ss, line);
  out.sections = static_cast<std::size_t>(ss.body_last - ss.body_first + 1);
  for (const auto& s : ss.secs) {
    if (!s.body || s.rejected) continue;
    out.centres.push_back(fr.xy(s.a + 0.5, s.centre));
    out.widths.push_back(s.width);
  }
  if (out.centres.size() < 10) throw Error(where, "too few usable cross-sections on a side of the mark");
  out.width = median(out.widths);
  out.darkness = ss.darkness;

  const Line2 body_line = evaluation::fit_line_tls(out.centres).line;
  for (const bool low : {true, false}) {
    if (!(low ? low_free : high_free)) continue;
    const FreeEnd end = measure_free_end(ss, body_line, low, o);
    ((da > 0) == low ? out.start_cap : out.end_cap) = end.cap;
    if (end.continues) {
      throw Error(where, fmt::format("the mark goes on past the end of a side near {}, so that end "
                                     "cannot be measured: it is not a free end (a corner that was not found, or a mark with "
                                     "more sides than asked for)", position_text(end.cap, px_per_m, o)));
    }
    if (!end.round) {
      out.end_uncertainty += end.uncertainty_px;
      out.warnings.push_back(fmt::format("the mark's end near {} is not a round laser-spot end "
                                         "(tip radius {:.3f} mm for a {:.3f} mm wide mark); its position along the side may be off "
                                         "by up to {:.3f} mm", position_text(end.cap, px_per_m, o), to_mm(end.radius),
                                         to_mm(out.width), to_mm(end.uncertainty_px)));
    }
  }
  if (da < 0) std::reverse(out.centres.begin(), out.centres.end()), std::reverse(out.widths.begin(), out.widths.end());
  return out;
}

}  // namespace stiffpath::vision::detail
