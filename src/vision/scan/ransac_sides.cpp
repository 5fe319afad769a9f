// Straight sides of a mark on the coarse grid by sequential RANSAC: the heaviest gap-free run of cells near each line.
#include <algorithm>
#include <fmt/format.h>
#include <random>

#include "side_search.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision::detail {

namespace {

using evaluation::Line2;

// The heaviest run of inliers along the line without gaps longer than `max_gap`.
std::vector<std::size_t> heaviest_run(const MarkComponent& m, const std::vector<std::size_t>& inliers, const Line2& line,
                                      double max_gap) {
  std::vector<std::size_t> sorted = inliers;
  std::sort(sorted.begin(), sorted.end(),
            [&](std::size_t a, std::size_t b) { return line.along(m.cells_px[a]) < line.along(m.cells_px[b]); });
  std::vector<std::size_t> best, run;
  double best_mass = -1, mass = 0;
  for (std::size_t k = 0; k <= sorted.size(); ++k) {
    const bool gap = k == sorted.size() ||
                     (k > 0 && line.along(m.cells_px[sorted[k]]) - line.along(m.cells_px[sorted[k - 1]]) > max_gap);
    if (gap) {
      if (mass > best_mass) best_mass = mass, best = run;
      run.clear();
      mass = 0;
    }
    if (k < sorted.size()) run.push_back(sorted[k]), mass += m.weights[sorted[k]];
  }
  return best;
}

}  // namespace

FoundSide fit_cells(const MarkComponent& m, const std::vector<std::size_t>& idx) {
  std::vector<Point2> pts;
  std::vector<double> w;
  for (const auto i : idx) pts.push_back(m.cells_px[i]), w.push_back(std::max(1e-6, m.weights[i]));
  FoundSide f;
  f.line = evaluation::fit_line_tls(pts, w).line;
  f.t0 = 1e300, f.t1 = -1e300;
  for (const auto& p : pts) f.t0 = std::min(f.t0, f.line.along(p)), f.t1 = std::max(f.t1, f.line.along(p));
  return f;
}

std::vector<FoundSide> ransac_sides(const MarkComponent& m, int n, const SideSearch& s, const SourceLocation& where) {
  std::vector<std::size_t> remaining(m.cells_px.size());
  for (std::size_t i = 0; i < remaining.size(); ++i) remaining[i] = i;
  double total = 0;
  for (const double w : m.weights) total += w;
  std::mt19937_64 rng(s.seed);
  std::vector<FoundSide> found;
  for (int k = 0; k < n; ++k) {
    if (remaining.size() < 2) break;
    std::uniform_int_distribution<std::size_t> pick(0, remaining.size() - 1);
    Line2 best;
    double best_score = -1;
    for (int it = 0; it < s.trials; ++it) {
      const Point2 a = m.cells_px[remaining[pick(rng)]], b = m.cells_px[remaining[pick(rng)]];
      if ((b - a).norm() < 4 * s.band) continue;
      const Line2 line{a, (b - a).normalized()};
      double score = 0;
      for (const auto i : remaining) {
        if (std::abs(line.offset(m.cells_px[i])) <= s.band) score += m.weights[i];
      }
      if (score > best_score) best_score = score, best = line;
    }
    if (best_score < 0) break;
    std::vector<std::size_t> run;
    for (int pass = 0; pass < 3; ++pass) {
      std::vector<std::size_t> inliers;
      for (const auto i : remaining) {
        if (std::abs(best.offset(m.cells_px[i])) <= s.band) inliers.push_back(i);
      }
      run = heaviest_run(m, inliers, best, s.max_gap);
      if (run.size() < 2) break;
      best = fit_cells(m, run).line;
    }
    if (run.size() < 2) break;
    FoundSide side = fit_cells(m, run);
    if (side.t1 - side.t0 < s.min_length) break;
    found.push_back(side);
    std::vector<std::size_t> left;
    for (const auto i : remaining) {
      const double t = side.line.along(m.cells_px[i]);
      const bool on = std::abs(side.line.offset(m.cells_px[i])) <= s.band + 1.0 && t >= side.t0 - s.band && t <= side.t1 + s.band;
      if (!on) left.push_back(i);
    }
    remaining.swap(left);
  }
  if (static_cast<int>(found.size()) < n) {
    throw Error(where, fmt::format("the mark does not split into {} straight sides (found {} longer than {:.1f} px)", n,
                                   found.size(), s.min_length));
  }
  double left_mass = 0;
  for (const auto i : remaining) left_mass += m.weights[i];
  if (left_mass > s.unassigned_fraction * total) {
    throw Error(where, fmt::format("the mark has more than {} straight sides: {:.0f} % of it lies on none of them", n,
                                   100 * left_mass / total));
  }
  return found;
}

}  // namespace stiffpath::vision::detail
