// Prediction uncertainty: thin-plate kriging variance of the measured points, scales from leave-one-out errors.
#include "stiffpath/compliance/uncertainty.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

namespace {
// The thin-plate kernel φ(r) = r²·log r from r², as the residual spline uses it.
double thin_plate(double r2) noexcept { return r2 > 0.0 ? 0.5 * r2 * std::log(r2) : 0.0; }

// Positions closer than this are the same measurement point (the tables' grid tolerance).
constexpr double kSamePoint_m = 1e-6;

// The entries c11, c12, c21, c22 of C.
std::array<double, 4> entries(const Mat2& c) { return {c(0, 0), c(0, 1), c(1, 0), c(1, 1)}; }
}  // namespace

const char* to_string(UncertaintyBasis basis) noexcept {
  return basis == UncertaintyBasis::interpolation ? "interpolation" : "stationary";
}

InterpolationVariance::InterpolationVariance(std::vector<Vec2> nodes_m, double smoothing)
    : nodes_(std::move(nodes_m)), smoothing_(smoothing) {
  const auto n = static_cast<Eigen::Index>(nodes_.size());
  if (n < 3) throw Error(fmt::format("interpolation variance: needs at least 3 points, got {}", n));
  auto b = GridBounds::none();
  for (const auto& p : nodes_) b.include(p);
  origin_ = Vec2(b.x_min, b.y_min);
  scale_ = std::max(b.x_max - b.x_min, b.y_max - b.y_min);
  if (!(scale_ > 0.0)) throw Error("interpolation variance: the points coincide");
  for (const auto& p : nodes_) unit_.push_back((p - origin_) / scale_);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 3, n + 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec2& qi = unit_[static_cast<std::size_t>(i)];
    for (Eigen::Index j = 0; j < n; ++j) A(i, j) = thin_plate((qi - unit_[static_cast<std::size_t>(j)]).squaredNorm());
    A(i, i) += smoothing_;
    A(i, n) = A(n, i) = 1.0;
    A(i, n + 1) = A(n + 1, i) = qi.x();
    A(i, n + 2) = A(n + 2, i) = qi.y();
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (lu.rank() < n + 3) throw Error("interpolation variance: the points lie on one line");
  inverse_ = lu.inverse();
}

double InterpolationVariance::at(const Vec2& p) const {
  const auto n = static_cast<Eigen::Index>(unit_.size());
  const Vec2 q = (p - origin_) / scale_;
  Eigen::VectorXd k(n + 3);
  for (Eigen::Index i = 0; i < n; ++i) k(i) = thin_plate((q - unit_[static_cast<std::size_t>(i)]).squaredNorm());
  k(n) = 1.0;
  k(n + 1) = q.x();
  k(n + 2) = q.y();
  return std::max(0.0, -k.dot(inverse_ * k));
}

std::array<double, 4> PredictionUncertainty::entry_variance(const Vec2& p) const {
  std::array<double, 4> v = floor_m2_per_N2;
  if (field) {
    const double unit = field->at(p);
    for (std::size_t c = 0; c < 4; ++c) v[c] += scale_m2_per_N2[c] * unit;
  }
  return v;
}

Mat2 PredictionUncertainty::deflection_covariance(const Vec2& p, const Vec2& F) const {
  // Δx = c11·Fx + c12·Fy, Δy = c21·Fx + c22·Fy with independent entries (c12 ≡ c21 when symmetric).
  const auto v = entry_variance(p);
  Mat2 cov;
  cov(0, 0) = v[0] * F.x() * F.x() + v[1] * F.y() * F.y();
  cov(1, 1) = v[2] * F.x() * F.x() + v[3] * F.y() * F.y();
  cov(0, 1) = cov(1, 0) = symmetric ? v[1] * F.x() * F.y() : 0.0;
  return cov;
}

Mat2 PredictionUncertainty::measurement_covariance(const Vec2& p, const Vec2& F) const {
  Mat2 cov = deflection_covariance(p, F);
  cov(0, 0) += campaign_sigma_m.x() * campaign_sigma_m.x();
  cov(1, 1) += campaign_sigma_m.y() * campaign_sigma_m.y();
  return cov;
}

double student_t_975(int dof) noexcept {
  // The 97.5 % quantile of Student's t for 1 … 30 degrees of freedom; beyond, the Cornish–Fisher expansion about
  // the normal quantile (within 10⁻⁴ there).
  static constexpr double kTable[30] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                        2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                        2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof < 1) return std::numeric_limits<double>::infinity();
  if (dof <= 30) return kTable[dof - 1];
  const double z = kBand95, nu = dof, z3 = z * z * z, z5 = z3 * z * z;
  return z + (z3 + z) / (4.0 * nu) + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * nu * nu);
}

double PredictionUncertainty::band_factor() const noexcept { return student_t_975(degrees_of_freedom); }

UncertaintyBasis uncertainty_basis(FitMethod method) {
  return method == FitMethod::physical || method == FitMethod::physical_0 || method == FitMethod::physical_2 ? UncertaintyBasis::stationary
                                                                                  : UncertaintyBasis::interpolation;
}

PredictionUncertainty estimate_uncertainty(const std::vector<PointSamples>& training, const std::vector<LooResidual>& loo,
                                           UncertaintyBasis basis, bool symmetric, const std::string& source) {
  if (loo.empty()) throw Error(SourceLocation{source}, "prediction uncertainty: no leave-one-out predictions to learn it from");
  PredictionUncertainty u;
  u.degrees_of_freedom = std::max(1, static_cast<int>(loo.size()) - (basis == UncertaintyBasis::interpolation ? 1 : 2));
  u.basis = basis;
  u.symmetric = symmetric;
  u.held_out = static_cast<int>(loo.size());
  // The per-point fits: their slopes' variance, and the cells' scatter about slope·F (intercept and noise).
  std::array<double, 4> fit_variance{};
  Vec2 scatter = Vec2::Zero(), cells = Vec2::Zero(), series = Vec2::Zero();
  for (const auto& point : training) {
    const PointFit f = fit_point(point, source);
    const LineFit* lines[4] = {&f.dx_fx, &f.dx_fy, &f.dy_fx, &f.dy_fy};
    for (std::size_t c = 0; c < 4; ++c) fit_variance[c] += lines[c]->slope_stderr * lines[c]->slope_stderr / static_cast<double>(training.size());
    const Mat2 C = f.compliance();
    for (const auto& s : point.samples) {
      const Vec2 d = C * s.force_N;
      if (s.dx_m) {
        scatter.x() += (*s.dx_m - d.x()) * (*s.dx_m - d.x());
        cells.x() += 1.0;
      }
      if (s.dy_m) {
        scatter.y() += (*s.dy_m - d.y()) * (*s.dy_m - d.y());
        cells.y() += 1.0;
      }
    }
    series += Vec2(2.0, 2.0);  // each axis has an x-loaded and a y-loaded line, each with its slope fitted
  }
  for (int a = 0; a < 2; ++a) {
    u.campaign_sigma_m[a] = cells[a] > series[a] ? std::sqrt(scatter[a] / (cells[a] - series[a])) : 0.0;
  }
  if (training.size() < 4) {
    throw Error(SourceLocation{source}, "prediction uncertainty: needs at least 4 measured points");
  }
  std::vector<Vec2> positions;
  for (const auto& p : training) positions.push_back(p.position);
  u.field.emplace(positions, kUncertaintySmoothing);
  // Each held-out point's interpolation variance, taken without it (as its prediction was made).
  std::vector<double> v;
  std::vector<std::array<double, 4>> e2;
  for (const auto& r : loo) {
    std::vector<Vec2> others;
    for (const auto& p : positions) {
      if ((p - r.position).norm() > kSamePoint_m) others.push_back(p);
    }
    v.push_back(others.size() >= 3 ? InterpolationVariance(others, kUncertaintySmoothing).at(r.position) : 0.0);
    const auto e = entries(r.error);
    e2.push_back({e[0] * e[0], e[1] * e[1], e[2] * e[2], e[3] * e[3]});
  }
  const auto n = static_cast<double>(loo.size());
  for (std::size_t c = 0; c < 4; ++c) {
    // E² less the held-out point's own fit variance, against v.
    double sum_y = 0.0, sum_v = 0.0, sum_vv = 0.0, sum_vy = 0.0, sum_ratio = 0.0;
    int ratios = 0;
    for (std::size_t k = 0; k < loo.size(); ++k) {
      const double y = e2[k][c] - fit_variance[c];
      sum_y += y;
      sum_v += v[k];
      sum_vv += v[k] * v[k];
      sum_vy += v[k] * y;
      if (v[k] > 0.0) {
        sum_ratio += y / v[k];
        ++ratios;
      }
    }
    if (basis == UncertaintyBasis::interpolation) {
      // Through the points: the floor is the fits' own variance, the scale the mean of (E² − floor)/v.
      u.floor_m2_per_N2[c] = fit_variance[c];
      u.scale_m2_per_N2[c] = ratios > 0 ? std::max(0.0, sum_ratio / ratios) : 0.0;
    } else {
      // Not through them: misfit + scale·v by least squares on (v, E² − fit variance), both ≥ 0.
      double floor = 0.0, scale = 0.0;
      const double det = n * sum_vv - sum_v * sum_v;
      if (det > 0.0) {
        floor = (sum_vv * sum_y - sum_v * sum_vy) / det;
        scale = (n * sum_vy - sum_v * sum_y) / det;
      }
      if (!(det > 0.0) || scale < 0.0) {
        scale = 0.0;
        floor = sum_y / n;
      } else if (floor < 0.0) {
        floor = 0.0;
        scale = sum_vv > 0.0 ? std::max(0.0, sum_vy / sum_vv) : 0.0;
      }
      u.floor_m2_per_N2[c] = std::max(floor, 0.0) + fit_variance[c];
      u.scale_m2_per_N2[c] = scale;
    }
  }
  if (symmetric) {  // one off-diagonal entry, seen twice
    u.floor_m2_per_N2[1] = u.floor_m2_per_N2[2] = 0.5 * (u.floor_m2_per_N2[1] + u.floor_m2_per_N2[2]);
    u.scale_m2_per_N2[1] = u.scale_m2_per_N2[2] = 0.5 * (u.scale_m2_per_N2[1] + u.scale_m2_per_N2[2]);
  }
  return u;
}

PredictionUncertainty estimate_method_uncertainty(FitMethod method, const std::vector<PointSamples>& points,
                                                  const kinematics::FiveBarGeometry& geometry, const std::string& source) {
  const auto predictions = leave_one_out_compliance(method, points, geometry, source);
  std::vector<LooResidual> loo;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!predictions[k].predicted) continue;
    loo.push_back({points[k].position, *predictions[k].predicted - fit_point(points[k], source).compliance()});
  }
  return estimate_uncertainty(points, loo, uncertainty_basis(method), method != FitMethod::bilinear, source);
}

}  // namespace stiffpath::compliance
