// Nonlinear least squares: Levenberg–Marquardt with bounds and scaling, and what the fit can and cannot tell.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace stiffpath::core {

//! Every constant of the solver, named, with its default. The defaults are Marquardt's scheme as the
//! project's fits have used it: damping relative to diag(JᵀJ), divided by 3 after a step that lowers the
//! cost and multiplied by 4 after one that does not.
struct LeastSquaresSettings {
  int max_iterations = 100;           //!< Jacobian evaluations (outer steps) of one run() call's default
  int max_tries_per_iteration = 10;   //!< damped solves per step before the run counts as stalled
  double initial_damping = 1e-2;      //!< λ at the start, relative to diag(JᵀJ) (Marquardt 1963)
  double damping_decrease = 3.0;      //!< λ ← max(λ / this, min_damping) after a step that lowers the cost
  double damping_increase = 4.0;      //!< λ ← λ · this after a step that does not
  double min_damping = 1e-9;          //!< λ's floor
  //! Added to diag(JᵀJ) in the damping term, so that a parameter whose column is zero is still damped.
  double diagonal_floor = 1e-30;
  //! The run has converged when a step lowers the cost (Σr²) by less than this fraction of it.
  double relative_decrease = 1e-10;
  //! Forward-difference step of the default Jacobian, in units of each parameter's scale.
  double finite_difference_step = 1e-6;
  //! A direction of the scaled Jacobian J·diag(scale) with singular value below this fraction of the
  //! largest is undetermined by the residuals: the readings cannot separate the parameters along it.
  double undetermined_ratio = 1e-6;
};

//! A least-squares problem: minimise Σ r_i(x)² over x, each x_k within [lower_k, upper_k].
struct LeastSquaresProblem {
  //! The residual vector at x (its length must not change between calls).
  std::function<Eigen::VectorXd(const Eigen::VectorXd& x)> residuals;
  //! ∂r/∂x at x, given r(x) (columns of fixed parameters are ignored); empty: forward differences with a
  //! step of finite_difference_step × scale_k, projected into the bounds.
  std::function<Eigen::MatrixXd(const Eigen::VectorXd& x, const Eigen::VectorXd& r)> jacobian;
  Eigen::VectorXd lower;  //!< lower bounds; empty: none (−∞ entries allowed)
  Eigen::VectorXd upper;  //!< upper bounds; empty: none (+∞ entries allowed)
  //! Each parameter's typical size (its prior uncertainty or plausible range), > 0: the unit of the
  //! finite-difference step and of the identifiability analysis. Empty: 1 for every parameter.
  Eigen::VectorXd scale;
  //! Parameters held at their start value; empty: none.
  std::vector<bool> fixed;
};

//! Why a run stopped.
enum class LeastSquaresStop {
  running,          //!< not stopped: run() may continue it
  converged,        //!< the last accepted step lowered the cost by less than relative_decrease
  stalled,          //!< no damping in max_tries_per_iteration lowered the cost
  iteration_limit,  //!< the last run() call used all its iterations
};
const char* to_string(LeastSquaresStop stop) noexcept;

//! What the residuals determine at a solution: the scaled Jacobian's singular values, its undetermined
//! directions and the covariance of the estimate.
struct LeastSquaresStatistics {
  std::vector<int> free;              //!< the parameters that were fitted (indices into x)
  Eigen::MatrixXd jacobian;           //!< ∂r/∂x at the solution, every parameter's column
  //! Singular values of J·diag(scale) over the free parameters, largest first.
  Eigen::VectorXd singular_values;
  //! Right singular vectors (columns, same order), over the free parameters in scaled units.
  Eigen::MatrixXd directions;
  int rank = 0;  //!< singular values ≥ undetermined_ratio × the largest
  //! Residual σ behind the covariance: the given noise, or √(Σr² / (m − rank)) estimated from the residuals.
  double sigma = 0.0;
  bool sigma_estimated = true;
  int degrees_of_freedom = 0;  //!< m − rank
  //! σ²·(JᵀJ)⁺ over every parameter (fixed ones: zero rows and columns), the pseudo-inverse taken on the
  //! determined directions only: a parameter with a part in an undetermined direction has no meaningful
  //! variance (see undetermined()).
  Eigen::MatrixXd covariance;
  //! The undetermined directions (columns of `directions` beyond `rank`), each over every parameter in
  //! scaled units (fixed ones zero).
  [[nodiscard]] std::vector<Eigen::VectorXd> undetermined() const;
  //! √diag(covariance).
  [[nodiscard]] Eigen::VectorXd standard_errors() const;
};

//! The result of a run.
struct LeastSquaresResult {
  Eigen::VectorXd x;
  Eigen::VectorXd residuals;
  double cost = 0.0;  //!< Σr²
  int iterations = 0;
  int evaluations = 0;  //!< residual evaluations, the Jacobian's excluded
  LeastSquaresStop stop = LeastSquaresStop::running;
  std::vector<bool> at_bound;  //!< parameters that ended on a bound (their covariance does not apply)
  std::optional<LeastSquaresStatistics> statistics;
};

//! A resumable Levenberg–Marquardt run (projected onto the bounds): run(n) continues exactly where the last
//! call stopped, so that a fit may screen several starts for a few steps and carry the best on.
class LevenbergMarquardt {
 public:
  //! Throws stiffpath::Error when the problem's vectors do not match x0 or a scale is not positive.
  LevenbergMarquardt(LeastSquaresProblem problem, Eigen::VectorXd x0, LeastSquaresSettings settings = {});

  //! Up to `iterations` more steps (default: settings.max_iterations); returns the stop reason.
  LeastSquaresStop run(std::optional<int> iterations = std::nullopt);
  [[nodiscard]] const Eigen::VectorXd& x() const noexcept { return x_; }
  [[nodiscard]] const Eigen::VectorXd& residuals() const noexcept { return r_; }
  [[nodiscard]] double cost() const noexcept { return cost_; }
  [[nodiscard]] bool stopped() const noexcept { return stop_ == LeastSquaresStop::converged || stop_ == LeastSquaresStop::stalled; }
  [[nodiscard]] LeastSquaresStop stop() const noexcept { return stop_; }
  [[nodiscard]] double damping() const noexcept { return lambda_; }

  //! The result so far; with `statistics`, the Jacobian at x and what it determines, σ taken as
  //! `noise_sigma` when given (residuals in its unit) and estimated from the residuals otherwise.
  [[nodiscard]] LeastSquaresResult result(bool statistics = true, std::optional<double> noise_sigma = std::nullopt) const;

 private:
  [[nodiscard]] Eigen::MatrixXd jacobian_at(const Eigen::VectorXd& x, const Eigen::VectorXd& r) const;
  [[nodiscard]] Eigen::VectorXd project(Eigen::VectorXd x) const;

  LeastSquaresProblem problem_;
  LeastSquaresSettings settings_;
  std::vector<int> free_;
  Eigen::VectorXd x_, r_;
  double cost_ = 0.0;
  double lambda_ = 0.0;
  int iterations_ = 0;
  int evaluations_ = 0;
  LeastSquaresStop stop_ = LeastSquaresStop::running;
};

//! Minimises the problem from x0 (one run of settings.max_iterations) and returns the result with its statistics.
LeastSquaresResult least_squares(const LeastSquaresProblem& problem, const Eigen::VectorXd& x0,
                                 const LeastSquaresSettings& settings = {},
                                 std::optional<double> noise_sigma = std::nullopt);

//! What the columns of J (m × n, already in scaled units) determine: singular values, directions, rank
//! and σ²·(JᵀJ)⁺ on the determined directions, for residuals r (σ estimated unless `noise_sigma`).
//! `free` names the columns' parameters among `n_total`; `scale` (empty: 1) unscales the covariance.
LeastSquaresStatistics analyse_jacobian(const Eigen::MatrixXd& scaled_jacobian, const Eigen::VectorXd& residuals,
                                        const std::vector<int>& free, int n_total, const Eigen::VectorXd& scale,
                                        double undetermined_ratio, std::optional<double> noise_sigma);

//! Parameters to hold fixed so that the rest are determined: as many as J·diag(scale) has undetermined
//! directions (singular value < `undetermined_ratio` × the largest), chosen in the order of `preference`
//! (then by index): a parameter is fixed when the columns left keep the full rank. E.g. for a robot measured
//! in an instrument's frame, preferring the robot's own frame parameters fixes the gauge the data cannot see.
std::vector<int> parameters_to_fix(const Eigen::MatrixXd& scaled_jacobian, double undetermined_ratio,
                                   std::span<const int> preference = {});

}  // namespace stiffpath::core
