// Straight sides of the mark on the coarse grid: one TLS line, or RANSAC lines grown to their corners; corners link the sides in order.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

#include "side_search.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision::detail {

namespace {

using evaluation::Closure;

struct Link {
  double cost;
  int i, e, j, f;
  Point2 x;
};

// The loose ends of sides that did not meet, for an error message: where each end is and how far it is
// from the nearest crossing of its line with another side's.
std::string loose_ends(const std::vector<FoundSide>& found, const std::vector<std::array<int, 2>>& partner, double px_per_m,
                       const ScanOptions& options) {
  std::string out;
  const auto mm = [&](double px) { return px / px_per_m * 1e3; };
  for (std::size_t i = 0; i < found.size(); ++i) {
    for (int e = 0; e < 2; ++e) {
      if (partner[i][e] >= 0) continue;
      const Point2 end = found[i].line.at(e == 0 ? found[i].t0 : found[i].t1);
      double nearest = 1e300;
      for (std::size_t j = 0; j < found.size(); ++j) {
        if (j == i) continue;
        if (const auto x = evaluation::intersect(found[i].line, found[j].line)) nearest = std::min(nearest, (*x - end).norm());
      }
      out += fmt::format("{}side end at {}{}", out.empty() ? "" : "; ", position_text(end, px_per_m, options),
                         nearest < 1e299 ? fmt::format(" ({:.2f} mm from the nearest corner)", mm(nearest)) : "");
    }
  }
  return out;
}

}  // namespace

CoarsePath find_sides(const MarkComponent& mark, int n, double px_per_m, const ScanOptions& options) {
  const SourceLocation where{options.label, 0, 0};
  if (n < 1) throw Error(where, fmt::format("number of sides must be >= 1, got {}", n));
  const Closure closure = options.metrics.closure;
  if (closure == Closure::closed && n < 3) throw Error(where, fmt::format("a closed mark needs at least 3 sides, got {}", n));
  const ScanTuning& t = options.tuning;
  const double w = mark.width_px, cell_px = t.cell_px;
  SideSearch search;
  search.band = w / 2 + t.side_band_cells * cell_px;
  search.max_gap = std::max(t.side_gap_m * px_per_m, t.side_gap_widths * w);
  search.min_length = options.min_mark_length_m * px_per_m;
  search.trials = t.ransac_trials;
  search.seed = t.ransac_seed;
  search.unassigned_fraction = t.unassigned_fraction;
  // How far a side may stray from its line: the straightness allowed, plus the mark's width.
  const auto allowed_offset = [&](const FoundSide& side) {
    return std::max(t.straightness_m * px_per_m, t.straightness_fraction * (side.t1 - side.t0)) + w;
  };
  std::vector<FoundSide> found;
  std::vector<int> owner(mark.cells_px.size(), 0);
  if (n == 1) {
    std::vector<std::size_t> all(mark.cells_px.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    found.push_back(fit_cells(mark, all));
    double worst = 0;
    for (const auto& p : mark.cells_px) worst = std::max(worst, std::abs(found[0].line.offset(p)));
    const double allowed = allowed_offset(found[0]);
    if (worst > allowed) {
      throw Error(where, fmt::format("the mark is not a straight line: it strays {:.2f} mm from its fitted line; "
                                     "use --shape triangle or polyline:N", worst / px_per_m * 1e3));
    }
  } else {
    // Sides that bow (a robot deflected along its path) leave much of their mass outside a band of the
    // mark's width: widen the band step by step, up to the straightness allowed for a side.
    const double widest = std::max(t.widest_band_m * px_per_m, t.widest_band_widths * w);
    for (;;) {
      try {
        found = ransac_sides(mark, n, search, where);
        break;
      } catch (const Error&) {
        if (search.band >= widest) throw;
        search.band = std::min(2 * search.band, widest);
      }
    }
    owner = assign_cells(mark, found, t.assign_iterations, t.assign_settle_px);
    for (std::size_t k = 0; k < found.size(); ++k) {
      double worst = 0;
      for (std::size_t i = 0; i < owner.size(); ++i) {
        if (owner[i] == static_cast<int>(k)) worst = std::max(worst, std::abs(found[k].line.offset(mark.cells_px[i])));
      }
      const double allowed = allowed_offset(found[k]);
      if (worst > allowed) {
        throw Error(where, fmt::format("the mark does not split into {} straight sides: one strays {:.2f} mm from its fitted line "
                                       "(allowed {:.2f} mm)", n, worst / px_per_m * 1e3, allowed / px_per_m * 1e3));
      }
    }
  }

  // Link side ends that meet at the intersection of their lines.
  const double tol = std::max(t.corner_reach_m * px_per_m, t.corner_reach_widths * w);
  std::vector<Link> links;
  auto end_of = [&](int i, int e) { return found[i].line.at(e == 0 ? found[i].t0 : found[i].t1); };
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (evaluation::angle_between(found[i].line.direction, found[j].line.direction) < t.parallel_rad ||
          evaluation::angle_between(found[i].line.direction, -found[j].line.direction) < t.parallel_rad) continue;
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
  path.closed = n >= 3 && link_count == n;
  if (closure == Closure::closed && !path.closed) {
    throw Error(where, fmt::format("the {} sides found do not close into a loop, so the closed mark cannot be measured: {}", n,
                                   loose_ends(found, partner, px_per_m, options)));
  }
  if (link_count != (path.closed ? n : n - 1)) {
    throw Error(where, fmt::format("the {} sides found do not join into one path ({} of their corners meet): {}", n, link_count,
                                   loose_ends(found, partner, px_per_m, options)));
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
  std::vector<int> order;  // found index of each side of the chain
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
    order.push_back(side);
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
      std::reverse(order.begin(), order.end());
      for (auto& s : path.sides) std::swap(s.start, s.end), s.line.direction = -s.line.direction;
    }
  }
  for (int k = 0; k < n; ++k) {
    auto& s = path.sides[k];
    if (s.start_is_corner) s.start_angle_rad = evaluation::angle_between(-path.sides[(k + n - 1) % n].line.direction, s.line.direction);
    if (s.end_is_corner) s.end_angle_rad = evaluation::angle_between(-s.line.direction, path.sides[(k + 1) % n].line.direction);
  }
  // Which side of the chain owns each cell of the mark.
  std::vector<int> chain_of(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) chain_of[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])] = k;
  path.box = mark.box;
  path.width_px = mark.width_px;
  path.owner = cv::Mat(mark.box.size(), CV_8U, cv::Scalar(kNoSide));
  for (std::size_t i = 0; i < mark.cells_px.size(); ++i) {
    const int gx = static_cast<int>(mark.cells_px[i].x() / cell_px), gy = static_cast<int>(mark.cells_px[i].y() / cell_px);
    path.owner.at<std::uint8_t>(gy - mark.box.y, gx - mark.box.x) = static_cast<std::uint8_t>(chain_of[static_cast<std::size_t>(owner[i])]);
  }
  return path;
}

}  // namespace stiffpath::vision::detail
