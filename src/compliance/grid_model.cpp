// GridModel: bilinear interpolation of per-node compliance (eq. 4.12) and the thesis's bilinear model.
#include "stiffpath/compliance/grid_model.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

GridModel::GridModel(FitMethod method, Grid grid, std::vector<GridNode> nodes)
    : method_(std::move(method)), grid_(std::move(grid)), bounds_(grid_.bounds()), nodes_(std::move(nodes)) {
  if (nodes_.size() != grid_.xs.size() * grid_.ys.size()) {
    throw Error(fmt::format("grid model: {} nodes for a {} x {} grid", nodes_.size(), grid_.xs.size(), grid_.ys.size()));
  }
  for (const auto& n : nodes_) {
    compliance_.push_back(n.compliance);
    offset_.push_back(n.offset);
  }
  for (std::size_t i = 0; i + 1 < grid_.xs.size(); ++i) inverse_dx_.push_back(1.0 / (grid_.xs[i + 1] - grid_.xs[i]));
  for (std::size_t j = 0; j + 1 < grid_.ys.size(); ++j) inverse_dy_.push_back(1.0 / (grid_.ys[j + 1] - grid_.ys[j]));
}

namespace {
// Index of the cell [lines[k], lines[k+1]] holding v (edge cells beyond the ends); grids have a
// handful of lines, so a linear scan beats a binary search.
std::size_t cell_index(const std::vector<double>& lines, double v) noexcept {
  const std::size_t last = lines.size() - 2;
  std::size_t k = 0;
  while (k < last && v >= lines[k + 1]) ++k;
  return k;
}
}  // namespace

template <typename T>
T GridModel::interpolate(const Vec2& p, const std::vector<T>& values) const noexcept {
  const bool clamp = outside_policy() != OutsidePolicy::extrapolate;
  const double x = clamp ? std::clamp(p.x(), bounds_.x_min, bounds_.x_max) : p.x();
  const double y = clamp ? std::clamp(p.y(), bounds_.y_min, bounds_.y_max) : p.y();
  const std::size_t i = cell_index(grid_.xs, x), j = cell_index(grid_.ys, y), ny = grid_.ys.size();
  const double tx = (x - grid_.xs[i]) * inverse_dx_[i], ty = (y - grid_.ys[j]) * inverse_dy_[j];
  // Eq. 4.12: [x2 − x, x − x1] · [Δ11 Δ12; Δ21 Δ22] · [y2 − y; y − y1] / ((x2 − x1)(y2 − y1)).
  const double w00 = (1 - tx) * (1 - ty), w01 = (1 - tx) * ty, w10 = tx * (1 - ty), w11 = tx * ty;
  const T& v00 = values[i * ny + j];
  const T& v01 = values[i * ny + j + 1];
  const T& v10 = values[(i + 1) * ny + j];
  const T& v11 = values[(i + 1) * ny + j + 1];
  // Whole-matrix terms (Eigen adds two entries at a time), summed in the order of the written-out sum.
  return w00 * v00 + w01 * v01 + w10 * v10 + w11 * v11;
}

Mat2 GridModel::compliance(const Vec2& p) const noexcept { return interpolate(p, compliance_); }

void GridModel::compliance_batch(std::span<const Vec2> points, std::span<Mat2> out) const noexcept {
  for (std::size_t k = 0; k < points.size(); ++k) out[k] = interpolate(points[k], compliance_);
}

Vec2 GridModel::offset(const Vec2& p) const noexcept { return interpolate(p, offset_); }

nlohmann::json GridModel::parameters() const {
  nlohmann::json x_mm = nlohmann::json::array(), y_mm = nlohmann::json::array(), nodes = nlohmann::json::array();
  for (double x : grid_.xs) x_mm.push_back(x * 1e3);
  for (double y : grid_.ys) y_mm.push_back(y * 1e3);
  for (std::size_t i = 0; i < grid_.xs.size(); ++i) {
    for (std::size_t j = 0; j < grid_.ys.size(); ++j) {
      const GridNode& n = nodes_[i * grid_.ys.size() + j];
      const Mat2 c = n.compliance * 1e6;
      nodes.push_back({{"point", n.id},
                       {"x_mm", grid_.xs[i] * 1e3},
                       {"y_mm", grid_.ys[j] * 1e3},
                       {"C_um_per_N", {{c(0, 0), c(0, 1)}, {c(1, 0), c(1, 1)}}},
                       {"offset_um", {n.offset.x() * 1e6, n.offset.y() * 1e6}},
                       {"stats", n.stats}});
    }
  }
  return {{"grid", {{"x_mm", x_mm}, {"y_mm", y_mm}}}, {"nodes", nodes}};
}

namespace {
nlohmann::json line_stats(const LineFit& f) {
  return {{"slope_um_per_N", f.slope * 1e6},
          {"intercept_um", f.intercept * 1e6},
          {"slope_stderr_um_per_N", f.slope_stderr * 1e6},
          {"r_squared", f.r_squared},
          {"rms_residual_um", f.rms_residual * 1e6},
          {"n", f.n}};
}
}  // namespace

std::unique_ptr<GridModel> build_grid_model(FitMethod method, const std::vector<Vec2>& positions,
                                            const std::function<GridNode(std::size_t)>& make_node,
                                            const std::string& source) {
  std::vector<int> node_of;
  Grid grid = Grid::from_positions(positions, node_of, source);
  std::vector<GridNode> nodes(positions.size());
  for (std::size_t k = 0; k < positions.size(); ++k) nodes[static_cast<std::size_t>(node_of[k])] = make_node(k);
  return std::make_unique<GridModel>(std::move(method), std::move(grid), std::move(nodes));
}

std::unique_ptr<GridModel> make_bilinear_model(const std::vector<PointFit>& fits, const std::string& source) {
  std::vector<Vec2> positions;
  for (const auto& f : fits) positions.push_back(f.position);
  return build_grid_model(FitMethod::bilinear, positions, [&](std::size_t k) {
    const PointFit& f = fits[k];
    return GridNode{f.id, f.compliance(), f.offset(),
                    {{"dx_fx", line_stats(f.dx_fx)}, {"dx_fy", line_stats(f.dx_fy)},
                     {"dy_fx", line_stats(f.dy_fx)}, {"dy_fy", line_stats(f.dy_fy)}}};
  }, source);
}

}  // namespace stiffpath::compliance
