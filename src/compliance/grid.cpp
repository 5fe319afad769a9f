// Tensor-product measurement grid: construction from scattered points and cell location.
#include "stiffpath/compliance/grid.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

namespace {
constexpr double kTolerance = 1e-6;  // 1 µm: positions closer than this are the same grid line

std::vector<double> distinct(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  std::vector<double> out;
  for (double v : values) {
    if (out.empty() || v - out.back() > kTolerance) out.push_back(v);
  }
  return out;
}

int index_of(const std::vector<double>& lines, double v) {
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (std::abs(lines[k] - v) <= kTolerance) return static_cast<int>(k);
  }
  return -1;
}

// Index of the cell [lines[k], lines[k+1]] holding v (edge cells beyond the ends). Grids have a
// handful of lines, so a linear scan beats a binary search.
int cell(const std::vector<double>& lines, double v) {
  const std::size_t last = lines.size() - 2;
  std::size_t k = 0;
  while (k < last && v >= lines[k + 1]) ++k;
  return static_cast<int>(k);
}
}  // namespace

Grid Grid::from_positions(const std::vector<Vec2>& positions, std::vector<int>& node_of, const std::string& source) {
  Grid grid;
  std::vector<double> x, y;
  for (const auto& p : positions) {
    x.push_back(p.x());
    y.push_back(p.y());
  }
  grid.xs = distinct(x);
  grid.ys = distinct(y);
  if (grid.xs.size() < 2 || grid.ys.size() < 2) {
    throw Error(SourceLocation{source}, fmt::format("points span {} x value(s) and {} y value(s); a grid needs at "
                                                    "least 2 of each",
                                                    grid.xs.size(), grid.ys.size()));
  }
  std::vector<int> seen(grid.xs.size() * grid.ys.size(), -1);
  node_of.assign(positions.size(), -1);
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const int n = grid.node(index_of(grid.xs, positions[k].x()), index_of(grid.ys, positions[k].y()));
    if (seen[static_cast<std::size_t>(n)] >= 0) {
      throw Error(SourceLocation{source}, fmt::format("two points at ({:.3f}, {:.3f}) mm", positions[k].x() * 1e3,
                                                      positions[k].y() * 1e3));
    }
    seen[static_cast<std::size_t>(n)] = static_cast<int>(k);
    node_of[k] = n;
  }
  for (std::size_t i = 0; i < grid.xs.size(); ++i) {
    for (std::size_t j = 0; j < grid.ys.size(); ++j) {
      if (seen[i * grid.ys.size() + j] < 0) {
        throw Error(SourceLocation{source},
                    fmt::format("the points do not form a full grid: nothing measured at ({:.3f}, {:.3f}) mm",
                                grid.xs[i] * 1e3, grid.ys[j] * 1e3));
      }
    }
  }
  return grid;
}

void Grid::locate(const Vec2& p, int& i, int& j, double& tx, double& ty) const noexcept {
  i = cell(xs, p.x());
  j = cell(ys, p.y());
  const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
  tx = (p.x() - xs[ui]) / (xs[ui + 1] - xs[ui]);
  ty = (p.y() - ys[uj]) / (ys[uj + 1] - ys[uj]);
}

}  // namespace stiffpath::compliance
