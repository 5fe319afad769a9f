// Levenberg–Marquardt with bounds and scaling; the Jacobian's singular values, undetermined directions, covariance.
#include "stiffpath/core/least_squares.hpp"

#include <Eigen/Dense>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::core {

namespace {
// The columns `cols` of J.
Eigen::MatrixXd columns(const Eigen::MatrixXd& J, const std::vector<int>& cols) {
  if (static_cast<Eigen::Index>(cols.size()) == J.cols()) return J;
  Eigen::MatrixXd out(J.rows(), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t k = 0; k < cols.size(); ++k) out.col(static_cast<Eigen::Index>(k)) = J.col(cols[k]);
  return out;
}

// Numerical rank of J against the reference singular value `largest`.
int rank_of(const Eigen::MatrixXd& J, double largest, double ratio) {
  if (J.cols() == 0) return 0;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J);
  const Eigen::VectorXd& s = svd.singularValues();
  int r = 0;
  for (Eigen::Index k = 0; k < s.size(); ++k) r += s(k) >= ratio * largest && s(k) > 0.0 ? 1 : 0;
  return r;
}
}  // namespace

const char* to_string(LeastSquaresStop stop) noexcept {
  switch (stop) {
    case LeastSquaresStop::running: return "running";
    case LeastSquaresStop::converged: return "converged";
    case LeastSquaresStop::stalled: return "stalled";
    case LeastSquaresStop::iteration_limit: return "iteration limit";
  }
  return "?";
}

std::vector<Eigen::VectorXd> LeastSquaresStatistics::undetermined() const {
  std::vector<Eigen::VectorXd> out;
  const auto n_total = covariance.rows();
  for (Eigen::Index k = rank; k < directions.cols(); ++k) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(n_total);
    for (std::size_t j = 0; j < free.size(); ++j) v(free[j]) = directions(static_cast<Eigen::Index>(j), k);
    out.push_back(v);
  }
  return out;
}

Eigen::VectorXd LeastSquaresStatistics::standard_errors() const { return covariance.diagonal().cwiseMax(0.0).cwiseSqrt(); }

LevenbergMarquardt::LevenbergMarquardt(LeastSquaresProblem problem, Eigen::VectorXd x0, LeastSquaresSettings settings)
    : problem_(std::move(problem)), settings_(settings), x_(std::move(x0)) {
  const auto n = x_.size();
  if (!problem_.residuals) throw Error("least squares: no residual function");
  if (!x_.allFinite()) throw Error("least squares: the start is not finite");
  const auto check = [&](const Eigen::VectorXd& v, const char* what) {
    if (v.size() != 0 && v.size() != n) {
      throw Error(fmt::format("least squares: {} has {} entries for {} parameters", what, v.size(), n));
    }
  };
  check(problem_.lower, "lower");
  check(problem_.upper, "upper");
  check(problem_.scale, "scale");
  if (!problem_.fixed.empty() && static_cast<Eigen::Index>(problem_.fixed.size()) != n) {
    throw Error(fmt::format("least squares: fixed has {} entries for {} parameters", problem_.fixed.size(), n));
  }
  if (problem_.scale.size() == 0) problem_.scale = Eigen::VectorXd::Ones(n);
  if (!(problem_.scale.array() > 0.0).all() || !problem_.scale.allFinite()) {
    throw Error("least squares: every parameter's scale must be positive and finite");
  }
  if (!(settings_.damping_decrease > 1.0 && settings_.damping_increase > 1.0 && settings_.initial_damping > 0.0 &&
        settings_.max_tries_per_iteration > 0 && settings_.finite_difference_step > 0.0)) {
    throw Error("least squares: the damping factors must exceed 1 and the initial damping, tries and step be positive");
  }
  for (Eigen::Index k = 0; k < n; ++k) {
    if (problem_.fixed.empty() || !problem_.fixed[static_cast<std::size_t>(k)]) free_.push_back(static_cast<int>(k));
  }
  lambda_ = settings_.initial_damping;
  x_ = project(x_);
  r_ = problem_.residuals(x_);
  ++evaluations_;
  cost_ = r_.squaredNorm();
  if (!std::isfinite(cost_)) throw Error("least squares: the residuals at the start are not finite");
}

Eigen::VectorXd LevenbergMarquardt::project(Eigen::VectorXd x) const {
  if (problem_.lower.size() != 0) x = x.cwiseMax(problem_.lower);
  if (problem_.upper.size() != 0) x = x.cwiseMin(problem_.upper);
  return x;
}

Eigen::MatrixXd LevenbergMarquardt::jacobian_at(const Eigen::VectorXd& x, const Eigen::VectorXd& r) const {
  if (problem_.jacobian) {
    Eigen::MatrixXd J = problem_.jacobian(x, r);
    if (J.rows() != r.size() || J.cols() != x.size()) {
      throw Error(fmt::format("least squares: the Jacobian is {}×{}, expected {}×{}", J.rows(), J.cols(), r.size(), x.size()));
    }
    return J;
  }
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(r.size(), x.size());
  for (const int k : free_) {
    Eigen::VectorXd xp = x;
    double h = settings_.finite_difference_step * problem_.scale(k);
    // Step away from an upper bound rather than across it.
    if (problem_.upper.size() != 0 && x(k) + h > problem_.upper(k)) h = -h;
    xp(k) += h;
    J.col(k) = (problem_.residuals(xp) - r) / h;
  }
  return J;
}

LeastSquaresStop LevenbergMarquardt::run(std::optional<int> iterations) {
  if (stopped()) return stop_;
  const int steps = iterations.value_or(settings_.max_iterations);
  for (int it = 0; it < steps; ++it) {
    const Eigen::MatrixXd J = columns(jacobian_at(x_, r_), free_);
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r_;
    ++iterations_;
    bool improved = false, accepted = false;
    for (int tries = 0; tries < settings_.max_tries_per_iteration && !improved; ++tries) {
      Eigen::MatrixXd Ad = A;
      Ad.diagonal() += lambda_ * (A.diagonal().array() + settings_.diagonal_floor).matrix();
      const Eigen::VectorXd step = Ad.ldlt().solve(g);
      Eigen::VectorXd xn = x_;
      if (static_cast<Eigen::Index>(free_.size()) == x_.size()) {
        xn = x_ - step;
      } else {
        for (std::size_t j = 0; j < free_.size(); ++j) xn(free_[j]) -= step(static_cast<Eigen::Index>(j));
      }
      xn = project(std::move(xn));
      const Eigen::VectorXd rn = problem_.residuals(xn);
      ++evaluations_;
      const double cn = rn.squaredNorm();
      if (cn < cost_) {
        improved = (cost_ - cn) > settings_.relative_decrease * cost_;
        accepted = true;
        x_ = std::move(xn);
        r_ = rn;
        cost_ = cn;
        lambda_ = std::max(lambda_ / settings_.damping_decrease, settings_.min_damping);
        if (!improved) break;
      } else {
        lambda_ *= settings_.damping_increase;
      }
    }
    if (!improved) {
      // Either an accepted step too small to matter (converged) or no damping that lowers the cost (stalled).
      stop_ = accepted ? LeastSquaresStop::converged : LeastSquaresStop::stalled;
      return stop_;
    }
  }
  stop_ = LeastSquaresStop::iteration_limit;
  return stop_;
}

LeastSquaresResult LevenbergMarquardt::result(bool statistics, std::optional<double> noise_sigma) const {
  LeastSquaresResult out;
  out.x = x_;
  out.residuals = r_;
  out.cost = cost_;
  out.iterations = iterations_;
  out.evaluations = evaluations_;
  out.stop = stop_;
  out.at_bound.assign(static_cast<std::size_t>(x_.size()), false);
  for (Eigen::Index k = 0; k < x_.size(); ++k) {
    const bool low = problem_.lower.size() != 0 && x_(k) <= problem_.lower(k);
    const bool high = problem_.upper.size() != 0 && x_(k) >= problem_.upper(k);
    out.at_bound[static_cast<std::size_t>(k)] = low || high;
  }
  if (statistics) {
    const Eigen::MatrixXd J = jacobian_at(x_, r_);
    Eigen::MatrixXd Js = columns(J, free_);
    for (std::size_t j = 0; j < free_.size(); ++j) Js.col(static_cast<Eigen::Index>(j)) *= problem_.scale(free_[j]);
    out.statistics = analyse_jacobian(Js, r_, free_, static_cast<int>(x_.size()), problem_.scale,
                                      settings_.undetermined_ratio, noise_sigma);
    out.statistics->jacobian = J;
  }
  return out;
}

LeastSquaresStatistics analyse_jacobian(const Eigen::MatrixXd& Js, const Eigen::VectorXd& r, const std::vector<int>& free,
                                        int n_total, const Eigen::VectorXd& scale, double ratio,
                                        std::optional<double> noise_sigma) {
  LeastSquaresStatistics s;
  s.free = free;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js, Eigen::ComputeThinV);
  s.singular_values = svd.singularValues();
  // JacobiSVD gives min(m, n) vectors; a direction beyond the residuals' count is undetermined as well.
  const auto nf = Js.cols();
  if (svd.matrixV().cols() == nf) {
    s.directions = svd.matrixV();
  } else {
    const Eigen::JacobiSVD<Eigen::MatrixXd> full(Js, Eigen::ComputeFullV);
    s.directions = full.matrixV();
    s.singular_values.conservativeResize(nf);
    s.singular_values.tail(nf - svd.singularValues().size()).setZero();
  }
  const double largest = s.singular_values.size() > 0 ? s.singular_values(0) : 0.0;
  s.rank = 0;
  for (Eigen::Index k = 0; k < s.singular_values.size(); ++k) {
    s.rank += s.singular_values(k) > 0.0 && s.singular_values(k) >= ratio * largest ? 1 : 0;
  }
  s.degrees_of_freedom = static_cast<int>(r.size()) - s.rank;
  if (noise_sigma) {
    s.sigma = *noise_sigma;
    s.sigma_estimated = false;
  } else {
    s.sigma = s.degrees_of_freedom > 0 ? std::sqrt(r.squaredNorm() / s.degrees_of_freedom) : 0.0;
  }
  // σ²·S·V_r·Σ_r⁻²·V_rᵀ·S on the free parameters.
  Eigen::MatrixXd cov_free = Eigen::MatrixXd::Zero(nf, nf);
  for (int k = 0; k < s.rank; ++k) {
    const Eigen::VectorXd v = s.directions.col(k);
    cov_free += v * v.transpose() / (s.singular_values(k) * s.singular_values(k));
  }
  s.covariance = Eigen::MatrixXd::Zero(n_total, n_total);
  for (Eigen::Index a = 0; a < nf; ++a) {
    for (Eigen::Index b = 0; b < nf; ++b) {
      const int i = free[static_cast<std::size_t>(a)], j = free[static_cast<std::size_t>(b)];
      const double si = scale.size() ? scale(i) : 1.0, sj = scale.size() ? scale(j) : 1.0;
      s.covariance(i, j) = s.sigma * s.sigma * si * sj * cov_free(a, b);
    }
  }
  return s;
}

LeastSquaresResult least_squares(const LeastSquaresProblem& problem, const Eigen::VectorXd& x0,
                                 const LeastSquaresSettings& settings, std::optional<double> noise_sigma) {
  LevenbergMarquardt lm(problem, x0, settings);
  lm.run();
  return lm.result(true, noise_sigma);
}

std::vector<int> parameters_to_fix(const Eigen::MatrixXd& Js, double ratio, std::span<const int> preference) {
  const auto n = static_cast<int>(Js.cols());
  if (n == 0) return {};
  const double largest = Eigen::JacobiSVD<Eigen::MatrixXd>(Js).singularValues()(0);
  const int rank = rank_of(Js, largest, ratio);
  std::vector<int> order(preference.begin(), preference.end());
  for (int k = 0; k < n; ++k) {
    if (std::find(order.begin(), order.end(), k) == order.end()) order.push_back(k);
  }
  std::vector<int> fixed;
  for (const int k : order) {
    if (static_cast<int>(fixed.size()) == n - rank) break;
    if (k < 0 || k >= n || std::find(fixed.begin(), fixed.end(), k) != fixed.end()) continue;
    std::vector<int> keep;
    for (int j = 0; j < n; ++j) {
      if (j != k && std::find(fixed.begin(), fixed.end(), j) == fixed.end()) keep.push_back(j);
    }
    if (rank_of(columns(Js, keep), largest, ratio) == rank) fixed.push_back(k);
  }
  std::sort(fixed.begin(), fixed.end());
  return fixed;
}

}  // namespace stiffpath::core
