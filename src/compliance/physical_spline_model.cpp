// The physical model plus a thin-plate smoothing spline of its residual at the measured points, read from a lattice.
#include "stiffpath/compliance/physical_spline_model.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

namespace {
// The thin-plate kernel φ(r) = r²·log r, from r² (φ = ½·r²·log r²); φ(0) = 0.
double thin_plate(double r2) noexcept { return r2 > 0.0 ? 0.5 * r2 * std::log(r2) : 0.0; }

// The lattice's spacing: 1/200 of the measured rectangle's larger side (0.75 mm for the thesis's 150 mm),
// at most 200 × 200 cells over it whatever the robot's size.
double lattice_spacing(const GridBounds& b) { return std::max(b.x_max - b.x_min, b.y_max - b.y_min) / 200.0; }
// The lattice follows the formula to 10⁻⁵ (relative): 0.007 µm of a 700 µm deflection. The thin-plate
// kernel's curvature has a logarithmic peak at each node, where a tighter bound would leave cells to the
// formula (50 of the thesis's 27 000 at 10⁻⁶).
constexpr double kLatticeTolerance = 1e-5;
}  // namespace

Mat2 ResidualSpline::at(const Vec2& p) const noexcept {
  const Vec2 q = (p - origin_m) / scale_m;
  double r[3];
  for (std::size_t c = 0; c < 3; ++c) r[c] = affine[0][c] + affine[1][c] * q.x() + affine[2][c] * q.y();
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const double phi = thin_plate((q - nodes[k]).squaredNorm());
    for (std::size_t c = 0; c < 3; ++c) r[c] += weights[k][c] * phi;
  }
  Mat2 out;
  out << r[0], r[1], r[1], r[2];
  return out;
}

ResidualSpline fit_residual_spline(const std::vector<Vec2>& positions, const std::vector<Mat2>& values,
                                   double smoothing, const std::string& source) {
  const std::size_t n = positions.size();
  if (n < 3 || values.size() != n) {
    throw Error(SourceLocation{source}, fmt::format("the residual spline needs at least 3 measured points, got {}", n));
  }
  if (!(std::isfinite(smoothing) && smoothing >= 0.0)) {
    throw Error(SourceLocation{source}, fmt::format("the residual spline's smoothing must be >= 0, got {}", smoothing));
  }
  auto b = GridBounds::none();
  for (const auto& p : positions) b.include(p);
  ResidualSpline s;
  s.origin_m = Vec2(b.x_min, b.y_min);
  s.scale_m = std::max(b.x_max - b.x_min, b.y_max - b.y_min);
  s.smoothing = smoothing;
  if (!(s.scale_m > 0.0)) throw Error(SourceLocation{source}, "the residual spline needs points spread over x or y");
  for (const auto& p : positions) s.nodes.push_back((p - s.origin_m) / s.scale_m);
  // [Φ + λI  P; Pᵀ 0]·[w; a] = [R; 0], P = [1 qx qy]: the smoothing thin-plate spline's normal equations.
  const auto N = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(N + 3, N + 3);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(N + 3, 3);
  for (Eigen::Index i = 0; i < N; ++i) {
    const Vec2& qi = s.nodes[static_cast<std::size_t>(i)];
    for (Eigen::Index j = 0; j < N; ++j) A(i, j) = thin_plate((qi - s.nodes[static_cast<std::size_t>(j)]).squaredNorm());
    A(i, i) += smoothing;
    A(i, N) = A(N, i) = 1.0;
    A(i, N + 1) = A(N + 1, i) = qi.x();
    A(i, N + 2) = A(N + 2, i) = qi.y();
    const Mat2& v = values[static_cast<std::size_t>(i)];
    // In µm/N so that the solution is O(1).
    rhs(i, 0) = v(0, 0) * 1e6;
    rhs(i, 1) = 0.5 * (v(0, 1) + v(1, 0)) * 1e6;
    rhs(i, 2) = v(1, 1) * 1e6;
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (lu.rank() < N + 3) {
    throw Error(SourceLocation{source},
                "the residual spline needs measured points that do not all lie on one line (its affine part is undetermined)");
  }
  const Eigen::MatrixXd sol = lu.solve(rhs);
  if (!sol.allFinite()) throw Error(SourceLocation{source}, "the residual spline's system has no finite solution");
  for (Eigen::Index i = 0; i < N; ++i) s.weights.push_back({sol(i, 0) * 1e-6, sol(i, 1) * 1e-6, sol(i, 2) * 1e-6});
  for (std::size_t t = 0; t < 3; ++t) {
    const auto row = N + static_cast<Eigen::Index>(t);
    s.affine[t] = {sol(row, 0) * 1e-6, sol(row, 1) * 1e-6, sol(row, 2) * 1e-6};
  }
  return s;
}

PhysicalSplineModel::PhysicalSplineModel(std::unique_ptr<PhysicalModel> base, ResidualSpline residual,
                                         nlohmann::json stats, bool tabulate)
    : base_(std::move(base)), residual_(std::move(residual)), stats_(std::move(stats)) {
  if (!base_) throw Error("physical-spline model: no physical model");
  if (residual_.weights.size() != residual_.nodes.size() || !(residual_.scale_m > 0.0)) {
    throw Error("physical-spline model: the residual spline's nodes and weights do not match");
  }
  const OutsidePolicy policy = base_->outside_policy();
  set_zero_force(base_->zero_force());
  if (tabulate) {
    // The lattice covers the measured rectangle; its outer stencil nodes see the formula extended beyond it.
    base_->set_outside_policy(OutsidePolicy::extrapolate);
    lattice_.emplace(
        [this](const Vec2& p) -> Mat2 { return base_->compliance(p) + residual_.at(p); }, bounds(), lattice_spacing(bounds()),
        kLatticeTolerance);
  }
  set_outside_policy(policy);
}

void PhysicalSplineModel::set_outside_policy(OutsidePolicy policy) noexcept {
  Model::set_outside_policy(policy);
  base_->set_outside_policy(policy);
}

Mat2 PhysicalSplineModel::exact(const Vec2& p) const noexcept {
  return base_->compliance(p) + residual_.at(policy_point(p));
}

Mat2 PhysicalSplineModel::compliance(const Vec2& p) const noexcept {
  Mat2 c;
  return lattice_ && lattice_->read(p, c) ? c : exact(p);
}

nlohmann::json PhysicalSplineModel::parameters() const {
  nlohmann::json out = base_->parameters();
  nlohmann::json nodes = nlohmann::json::array(), weights = nlohmann::json::array(), affine = nlohmann::json::array();
  for (const auto& q : residual_.nodes) nodes.push_back({q.x(), q.y()});
  for (const auto& w : residual_.weights) weights.push_back({w[0] * 1e6, w[1] * 1e6, w[2] * 1e6});
  for (const auto& a : residual_.affine) affine.push_back({a[0] * 1e6, a[1] * 1e6, a[2] * 1e6});
  out["residual_spline"] = {{"kernel", "thin-plate r^2 log r"},
                            {"origin_mm", {residual_.origin_m.x() * 1e3, residual_.origin_m.y() * 1e3}},
                            {"scale_mm", residual_.scale_m * 1e3},
                            {"smoothing", residual_.smoothing},
                            {"nodes_unit", nodes},
                            {"weights_um_per_N", weights},
                            {"affine_um_per_N", affine}};
  out["stats"] = stats_;
  return out;
}

std::unique_ptr<PhysicalSplineModel> fit_physical_spline_model(const std::vector<PointSamples>& points,
                                                               const kinematics::FiveBarGeometry& geometry,
                                                               const std::string& source, bool tabulate) {
  auto physical = fit_physical_model(points, geometry, 1, source, tabulate);  // refits without a lattice skip the D check
  physical->set_outside_policy(OutsidePolicy::extrapolate);
  std::vector<Vec2> positions;
  std::vector<Mat2> residuals;
  double rms = 0.0;
  for (const auto& point : points) {
    const Mat2 measured = fit_point(point, source).compliance();
    positions.push_back(point.position);
    residuals.push_back(measured - physical->compliance(point.position));
    rms += residuals.back().squaredNorm();
  }
  ResidualSpline spline = fit_residual_spline(positions, residuals, kResidualSmoothing, source);
  nlohmann::json stats = physical->parameters()["stats"];
  stats["residual_rms_um_per_N"] = std::sqrt(rms / static_cast<double>(4 * points.size())) * 1e6;
  auto model = std::make_unique<PhysicalSplineModel>(std::move(physical), std::move(spline), std::move(stats), tabulate);
  model->set_outside_policy(OutsidePolicy::error);
  return model;
}

}  // namespace stiffpath::compliance
