// Straight sides of the mark on the coarse grid: one TLS line, or sequential RANSAC; corners link the sides in order.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <random>

#include "scan_internal.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision::detail {

namespace {

using evaluation::Line2;

struct Found {
  Line2 line;
  double t0 = 0, t1 = 0;  // extent along the line
};

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

Found fit_cells(const MarkComponent& m, const std::vector<std::size_t>& idx) {
  std::vector<Point2> pts;
  std::vector<double> w;
  for (const auto i : idx) pts.push_back(m.cells_px[i]), w.push_back(std::max(1e-6, m.weights[i]));
  Found f;
  f.line = evaluation::fit_line_tls(pts, w).line;
  f.t0 = 1e300, f.t1 = -1e300;
  for (const auto& p : pts) f.t0 = std::min(f.t0, f.line.along(p)), f.t1 = std::max(f.t1, f.line.along(p));
  return f;
}

std::vector<Found> ransac_sides(const MarkComponent& m, int n, double band, double max_gap, double min_len,
                                const SourceLocation& where) {
  std::vector<std::size_t> remaining(m.cells_px.size());
  for (std::size_t i = 0; i < remaining.size(); ++i) remaining[i] = i;
  double total = 0;
  for (const double w : m.weights) total += w;
  std::mt19937_64 rng(7);
  std::vector<Found> found;
  for (int k = 0; k < n; ++k) {
    if (remaining.size() < 2) break;
    std::uniform_int_distribution<std::size_t> pick(0, remaining.size() - 1);
    Line2 best;
    double best_score = -1;
    for (int it = 0; it < 600; ++it) {
      const Point2 a = m.cells_px[remaining[pick(rng)]], b = m.cells_px[remaining[pick(rng)]];
      if ((b - a).norm() < 4 * band) continue;
      const Line2 line{a, (b - a).normalized()};
      double score = 0;
      for (const auto i : remaining) {
        if (std::abs(line.offset(m.cells_px[i])) <= band) score += m.weights[i];
      }
      if (score > best_score) best_score = score, best = line;
    }
    if (best_score < 0) break;
    std::vector<std::size_t> run;
    for (int pass = 0; pass < 3; ++pass) {
      std::vector<std::size_t> inliers;
      for (const auto i : remaining) {
        if (std::abs(best.offset(m.cells_px[i])) <= band) inliers.push_back(i);
      }
      run = heaviest_run(m, inliers, best, max_gap);
      if (run.size() < 2) break;
      best = fit_cells(m, run).line;
    }
    if (run.size() < 2) break;
    Found side = fit_cells(m, run);
    if (side.t1 - side.t0 < min_len) break;
    found.push_back(side);
    std::vector<std::size_t> left;
    for (const auto i : remaining) {
      const double t = side.line.along(m.cells_px[i]);
      const bool on = std::abs(side.line.offset(m.cells_px[i])) <= band + 1.0 && t >= side.t0 - band && t <= side.t1 + band;
      if (!on) left.push_back(i);
    }
    remaining.swap(left);
  }
  if (static_cast<int>(found.size()) < n) {
    throw Error(where, fmt::format("the mark does not split into {} straight sides (found {} longer than {:.1f} px)", n,
                                   found.size(), min_len));
  }
  double left_mass = 0;
  for (const auto i : remaining) left_mass += m.weights[i];
  if (left_mass > 0.15 * total) {
    throw Error(where, fmt::format("the mark has more than {} straight sides: {:.0f} % of it lies on none of them", n,
                                   100 * left_mass / total));
  }
  return found;
}

}  // namespace

CoarsePath find_sides(const MarkComponent& mark, int n, double px_per_m, const ScanOptions& options) {
  const SourceLocation where{options.label, 0, 0};
  if (n < 1) throw Error(where, fmt::format("number of sides must be >= 1, got {}", n));
  const double w = mark.width_px, cell_px = options.cell_px;
  const double band = w / 2 + 1.5 * cell_px;
  const double min_len = options.min_mark_length_m * px_per_m;
  std::vector<Found> found;
  if (n == 1) {
    std::vector<std::size_t> all(mark.cells_px.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    found.push_back(fit_cells(mark, all));
    double worst = 0;
    for (const auto& p : mark.cells_px) worst = std::max(worst, std::abs(found[0].line.offset(p)));
    const double allowed = std::max(1e-3 * px_per_m, 0.03 * (found[0].t1 - found[0].t0)) + w;
    if (worst > allowed) {
      throw Error(where, fmt::format("the mark is not a straight line: it strays {:.2f} mm from its fitted line; "
                                     "use --shape triangle or polyline:N", worst / px_per_m * 1e3));
    }
  } else {
    found = ransac_sides(mark, n, band, std::max(1e-3 * px_per_m, 3 * w), min_len, where);
  }

  // Link side ends that meet at the intersection of their lines.
  const double tol = std::max(2e-3 * px_per_m, 4 * w);
  struct Link { double cost; int i, e, j, f; Point2 x; };
  std::vector<Link> links;
  auto end_of = [&](int i, int e) { return found[i].line.at(e == 0 ? found[i].t0 : found[i].t1); };
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (evaluation::angle_between(found[i].line.direction, found[j].line.direction) < 0.17 ||
          evaluation::angle_between(found[i].line.direction, -found[j].line.direction) < 0.17) continue;
      const auto x = evaluation::intersect(found[i].line, found[j].line);
      for (int e = 0; e < 2 && x; ++e) {
        for (int f = 0; f < 2; ++f) {
          const double di = (end_of(i, e) - *x).norm(), dj = (end_of(j, f) - *x).norm();
          if (std::max(di, dj) < tol) links.push_back({di + dj, i, e, j, f, *x});
        }
      }
    }
  }
  std::sort(links.begin(), links.end(), [](const Link& a, const Link& b) { return a.cost < b.cost; });
  std::vector<std::array<int, 2>> partner(n, {-1, -1});  // linked end index i*2+e, per side end
  std::vector<std::array<Point2, 2>> corner(n);
  int link_count = 0;
  for (const auto& l : links) {
    if (partner[l.i][l.e] >= 0 || partner[l.j][l.f] >= 0) continue;
    if (partner[l.i][1 - l.e] == l.j * 2 + 0 || partner[l.i][1 - l.e] == l.j * 2 + 1) continue;
    partner[l.i][l.e] = l.j * 2 + l.f;
    partner[l.j][l.f] = l.i * 2 + l.e;
    corner[l.i][l.e] = corner[l.j][l.f] = l.x;
    ++link_count;
  }
  CoarsePath path;
  path.closed = n >= 2 && link_count == n;
  if (link_count != (path.closed ? n : n - 1)) {
    throw Error(where, fmt::format("the {} sides found do not join into one path ({} of their corners meet)", n, link_count));
  }
  // Walk the chain from its start: the free end nearest the left edge, or for a loop the left-most corner.
  auto key = [](const Point2& p) { return p.x() + 1e-6 * p.y(); };
  int side = -1, entry = 0;
  for (int i = 0; i < n; ++i) {
    for (int e = 0; e < 2; ++e) {
      const bool candidate = path.closed ? partner[i][e] >= 0 : partner[i][e] < 0;
      if (!candidate) continue;
      const Point2 p = path.closed ? corner[i][e] : end_of(i, e);
      if (side < 0 || key(p) < key(path.closed ? corner[side][entry] : end_of(side, entry)) - 1e-9) side = i, entry = e;
    }
  }
  for (int step = 0; step < n; ++step) {
    CoarseSide s;
    const int exit = 1 - entry;
    s.start_is_corner = partner[side][entry] >= 0;
    s.end_is_corner = partner[side][exit] >= 0;
    s.start = s.start_is_corner ? corner[side][entry] : end_of(side, entry);
    s.end = s.end_is_corner ? corner[side][exit] : end_of(side, exit);
    s.line = found[side].line;
    if (s.line.direction.dot(s.end - s.start) < 0) s.line.direction = -s.line.direction;
    path.sides.push_back(s);
    if (!s.end_is_corner) break;
    const int next = partner[side][exit];
    side = next / 2;
    entry = next % 2;
  }
  if (static_cast<int>(path.sides.size()) != n) {
    throw Error(where, fmt::format("the {} sides found do not form one chain", n));
  }
  if (path.closed) {
    // Clockwise on screen (y down): positive shoelace sum of the corners.
    double area2 = 0;
    for (int k = 0; k < n; ++k) {
      const Point2 a = path.sides[k].start, b = path.sides[(k + 1) % n].start;
      area2 += a.x() * b.y() - b.x() * a.y();
    }
    if (area2 < 0) {
      std::reverse(path.sides.begin(), path.sides.end());
      for (auto& s : path.sides) std::swap(s.start, s.end), s.line.direction = -s.line.direction;
    }
  }
  for (int k = 0; k < n; ++k) {
    auto& s = path.sides[k];
    if (s.start_is_corner) s.start_angle_rad = evaluation::angle_between(-path.sides[(k + n - 1) % n].line.direction, s.line.direction);
    if (s.end_is_corner) s.end_angle_rad = evaluation::angle_between(-s.line.direction, path.sides[(k + 1) % n].line.direction);
  }
  return path;
}

}  // namespace stiffpath::vision::detail
