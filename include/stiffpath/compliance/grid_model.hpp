// Compliance on the measurement grid with bilinear interpolation between nodes (thesis eq. 4.12).
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stiffpath/compliance/grid.hpp"
#include "stiffpath/compliance/model.hpp"
#include "stiffpath/compliance/point_fit.hpp"

namespace stiffpath::compliance {

//! One grid node: the compliance matrix and zero-force deflection there, with its fit statistics.
struct GridNode {
  std::string id;          //!< "x1y1" …
  Mat2 compliance;         //!< m/N
  Vec2 offset;             //!< m (thesis_raw mode only)
  nlohmann::json stats;    //!< fit statistics, carried into model files
};

//! Node values interpolated bilinearly (eq. 4.12) over a tensor grid. Used by the thesis's model
//! ("bilinear": nodes from eqs. 4.8–4.11) and by the reciprocal model ("symmetric": nodes fitted
//! with C = Cᵀ ≻ 0). Outside the grid: clamp to the rectangle, or extend the edge cells linearly.
class GridModel final : public Model {
 public:
  //! `nodes` ordered by Grid::node(i, j); throws stiffpath::Error on a size mismatch.
  GridModel(FitMethod method, Grid grid, std::vector<GridNode> nodes);

  [[nodiscard]] std::optional<FitMethod> method() const noexcept override { return method_; }
  [[nodiscard]] std::string description() const override { return std::string(core::enum_name(method_)); }
  [[nodiscard]] Mat2 compliance(const Vec2& p) const noexcept override;
  //! The cell is located and weighted per point without any virtual call (the compensator's path).
  void compliance_batch(std::span<const Vec2> points, std::span<Mat2> out) const noexcept override;
  [[nodiscard]] Vec2 offset(const Vec2& p) const noexcept override;
  [[nodiscard]] GridBounds bounds() const noexcept override { return bounds_; }
  //! Its parameters and fit statistics as JSON, as model files hold them (compliance::model_parameters).
  [[nodiscard]] nlohmann::json parameters() const;

  [[nodiscard]] const Grid& grid() const noexcept { return grid_; }
  [[nodiscard]] const std::vector<GridNode>& nodes() const noexcept { return nodes_; }

 private:
  //! Eq. 4.12 at p (after the outside policy) over the node values `values`.
  template <typename T>
  [[nodiscard]] T interpolate(const Vec2& p, const std::vector<T>& values) const noexcept;

  FitMethod method_;
  Grid grid_;
  GridBounds bounds_;
  std::vector<GridNode> nodes_;
  // Compact copies of the nodes' values for the real-time path (15 × 48 bytes stay in cache), and
  // the reciprocal widths of the cells so that locating a point takes no division.
  std::vector<Mat2> compliance_;
  std::vector<Vec2> offset_;
  std::vector<double> inverse_dx_, inverse_dy_;
};

//! Places one node per point on the grid that `positions` form (Grid::from_positions checks it is
//! full); `make_node(k)` builds the node of point k.
std::unique_ptr<GridModel> build_grid_model(FitMethod method, const std::vector<Vec2>& positions,
                                            const std::function<GridNode(std::size_t)>& make_node,
                                            const std::string& source);

//! The thesis's model: eqs. 4.8–4.11 per point, eq. 4.12 between points.
std::unique_ptr<GridModel> make_bilinear_model(const std::vector<PointFit>& fits, const std::string& source);

//! Reciprocity-respecting model: per point, C = [c11 c12; c12 c22] fitted jointly to both load
//! directions (Maxwell–Betti), then projected onto the positive-definite cone (eigenvalues ≥ 1 nm/N);
//! bilinear between points, which keeps C symmetric positive definite inside the grid.
std::unique_ptr<GridModel> make_symmetric_model(const std::vector<PointSamples>& points, const std::string& source);

//! The symmetric fit at one point (exposed for cross-validation and tests).
GridNode fit_symmetric_node(const PointSamples& point, const std::string& source);

}  // namespace stiffpath::compliance
