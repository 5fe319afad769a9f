// The reciprocal (symmetric positive-definite) grid model: joint per-point fit with C = Cᵀ ≻ 0.
#include <Eigen/Dense>
#include <fmt/format.h>

#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

namespace {
constexpr double kMinEigenvalue = 1e-9;  // 1 nm/N (0.001 µm/N): the PD floor after projection
}

GridNode fit_symmetric_node(const PointSamples& point, const std::string& source) {
  // Unknowns: c11, c12, c22, then intercepts of (Δx|Fx), (Δy|Fx), (Δx|Fy), (Δy|Fy) as in eq. 4.8.
  std::vector<Eigen::Matrix<double, 1, 7>> rows;
  std::vector<double> rhs;
  int along_x = 0, along_y = 0;
  for (const auto& s : point.samples) {
    const bool x_load = s.force_N.y() == 0.0 && s.force_N.x() != 0.0;
    const bool y_load = s.force_N.x() == 0.0 && s.force_N.y() != 0.0;
    if (!x_load && !y_load) continue;
    const double f = x_load ? s.force_N.x() : s.force_N.y();
    if (s.dx_m) {
      Eigen::Matrix<double, 1, 7> r = Eigen::Matrix<double, 1, 7>::Zero();
      r(x_load ? 0 : 1) = f;
      r(x_load ? 3 : 5) = 1.0;
      rows.push_back(r);
      rhs.push_back(*s.dx_m);
    }
    if (s.dy_m) {
      Eigen::Matrix<double, 1, 7> r = Eigen::Matrix<double, 1, 7>::Zero();
      r(x_load ? 1 : 2) = f;
      r(x_load ? 4 : 6) = 1.0;
      rows.push_back(r);
      rhs.push_back(*s.dy_m);
    }
    (x_load ? along_x : along_y)++;
  }
  if (along_x < 2 || along_y < 2) {
    throw Error(SourceLocation{source}, fmt::format("point {}: the symmetric fit needs two load steps along x and "
                                                    "along y, found {} and {}",
                                                    point.id, along_x, along_y));
  }
  Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), 7);
  Eigen::VectorXd b(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    A.row(static_cast<Eigen::Index>(k)) = rows[k];
    b(static_cast<Eigen::Index>(k)) = rhs[k];
  }
  // Scale force columns to O(1) so that the solve is well conditioned (forces ~ 100 N, Δ ~ 1e-4 m).
  const double scale = 1e-2;
  A.leftCols(3) *= scale;
  const Eigen::VectorXd sol = A.colPivHouseholderQr().solve(b);
  const double rms = std::sqrt((A * sol - b).squaredNorm() / static_cast<double>(rows.size()));

  Mat2 c;
  c << sol(0) * scale, sol(1) * scale, sol(1) * scale, sol(2) * scale;
  const Eigen::SelfAdjointEigenSolver<Mat2> eig(c);
  Vec2 lambda = eig.eigenvalues();
  const bool projected = lambda.minCoeff() < kMinEigenvalue;
  lambda = lambda.cwiseMax(kMinEigenvalue);
  const Mat2 pd = eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();

  GridNode node;
  node.id = point.id;
  node.compliance = 0.5 * (pd + pd.transpose());
  node.offset = {sol(3) + sol(5), sol(4) + sol(6)};
  node.stats = {{"rms_residual_um", rms * 1e6},
                {"eigenvalues_um_per_N", {lambda(0) * 1e6, lambda(1) * 1e6}},
                {"projected_to_positive_definite", projected},
                {"equations", rows.size()}};
  return node;
}

std::unique_ptr<GridModel> make_symmetric_model(const std::vector<PointSamples>& points, const std::string& source) {
  std::vector<Vec2> positions;
  for (const auto& p : points) positions.push_back(p.position);
  return build_grid_model(FitMethod::symmetric, positions, [&](std::size_t k) { return fit_symmetric_node(points[k], source); },
                          source);
}

}  // namespace stiffpath::compliance
