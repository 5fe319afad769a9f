// Cells of a mark given to the nearest side segment, the segments' extents grown along bent ends to their corners.
#include <algorithm>
#include <cmath>

#include "side_search.hpp"

namespace stiffpath::vision::detail {

namespace {

double segment_distance(const FoundSide& s, const Point2& p) {
  const double t = s.line.along(p);
  return std::hypot(s.line.offset(p), std::max({0.0, s.t0 - t, t - s.t1}));
}

}  // namespace

std::vector<int> assign_cells(const MarkComponent& mark, std::vector<FoundSide>& sides, int iterations, double settle_px) {
  std::vector<int> owner(mark.cells_px.size(), 0);
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t i = 0; i < mark.cells_px.size(); ++i) {
      double best = 1e300;
      for (std::size_t k = 0; k < sides.size(); ++k) {
        const double d = segment_distance(sides[k], mark.cells_px[i]);
        if (d < best) best = d, owner[i] = static_cast<int>(k);
      }
    }
    double moved = 0;
    for (std::size_t k = 0; k < sides.size(); ++k) {
      double t0 = sides[k].t0, t1 = sides[k].t1;  // a side keeps at least the run it was found on
      for (std::size_t i = 0; i < mark.cells_px.size(); ++i) {
        if (owner[i] != static_cast<int>(k)) continue;
        const double t = sides[k].line.along(mark.cells_px[i]);
        t0 = std::min(t0, t), t1 = std::max(t1, t);
      }
      moved = std::max({moved, sides[k].t0 - t0, t1 - sides[k].t1});
      sides[k].t0 = t0, sides[k].t1 = t1;
    }
    if (moved < settle_px) break;
  }
  return owner;
}

}  // namespace stiffpath::vision::detail
