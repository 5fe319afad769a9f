// The uncertainty of a fitted compliance model's prediction, learnt from its own leave-one-out errors and the campaign's scatter.
#pragma once

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/compliance/physical_spline_model.hpp"
#include "stiffpath/compliance/point_fit.hpp"

namespace stiffpath::compliance {

//! The nugget λ of the interpolation variance: the residual spline's smoothing, so that v follows the spline that
//! physical-spline interpolates with.
inline constexpr double kUncertaintySmoothing = kResidualSmoothing;

//! The unit variance of interpolating a field from scattered nodes: the kriging variance of the thin-plate
//! spline (its generalised covariance φ(r) = r²·log r with the nugget λ, in the unit frame where the nodes'
//! rectangle spans 1 along its larger side), v(q) = −[φ(q); 1, q]ᵀ·[Φ + λI P; Pᵀ 0]⁻¹·[φ(q); 1, q]. About λ at
//! a node, growing between the nodes and beyond them: how far p is from what was measured.
class InterpolationVariance {
 public:
  InterpolationVariance() = default;
  //! Throws stiffpath::Error for fewer than 3 nodes or nodes all on one line.
  InterpolationVariance(std::vector<Vec2> nodes_m, double smoothing);
  [[nodiscard]] double at(const Vec2& p) const;
  [[nodiscard]] const std::vector<Vec2>& nodes() const noexcept { return nodes_; }
  [[nodiscard]] double smoothing() const noexcept { return smoothing_; }

 private:
  std::vector<Vec2> nodes_;       // m
  std::vector<Vec2> unit_;        // in the unit frame
  Vec2 origin_ = Vec2::Zero();
  double scale_ = 1.0;
  double smoothing_ = 0.0;
  Eigen::MatrixXd inverse_;       // [Φ + λI P; Pᵀ 0]⁻¹
};

//! How a model's error varies over the plane.
enum class UncertaintyBasis {
  interpolation,  //!< the model passes (nearly) through the measured points: error small there, growing away (grid
                  //!< models, physical-spline)
  stationary,     //!< a smooth model that does not pass through them: a misfit everywhere, growing away from the
                  //!< points as far as its leave-one-out errors say (physical)
};
const char* to_string(UncertaintyBasis basis) noexcept;

//! The uncertainty of a model's C(p) entries (c11, c12, c21, c22): floor + scale·v(p) with v the interpolation
//! variance of the measured points, each entry independent (for a symmetric model c12 ≡ c21); and the campaign's
//! scatter of one measured deflection about C·F (the series' zero-force intercepts and the instrument's noise),
//! per axis. A 95 % band is band_factor() standard deviations: Student's t for the degrees of freedom the scales
//! were learnt with (the leave-one-out points less the scales fitted per entry).
struct PredictionUncertainty {
  UncertaintyBasis basis = UncertaintyBasis::stationary;
  bool symmetric = false;
  std::array<double, 4> floor_m2_per_N2{};  //!< variance of each entry everywhere, (m/N)²
  std::array<double, 4> scale_m2_per_N2{};  //!< per unit of v(p) (interpolation basis)
  Vec2 campaign_sigma_m = Vec2::Zero();     //!< one measured deflection's scatter about C·F, x and y
  int held_out = 0;                         //!< leave-one-out predictions the scales were learnt from
  int degrees_of_freedom = 1;               //!< held_out − the scales fitted per entry (1 or 2)
  std::optional<InterpolationVariance> field;  //!< the measured points

  //! The 97.5 % quantile of Student's t with degrees_of_freedom: the half-width of a 95 % band in σ.
  [[nodiscard]] double band_factor() const noexcept;

  //! Variances of the four entries at p, (m/N)².
  [[nodiscard]] std::array<double, 4> entry_variance(const Vec2& p) const;
  //! Covariance of the predicted deflection C(p)·F against the true one (m²).
  [[nodiscard]] Mat2 deflection_covariance(const Vec2& p, const Vec2& F) const;
  //! Covariance of a measured deflection about the prediction: the above plus the campaign's scatter (m²).
  [[nodiscard]] Mat2 measurement_covariance(const Vec2& p, const Vec2& F) const;
};

//! A point's compliance predicted from the other points, against its own fit (eq. 4.8).
struct LooResidual {
  Vec2 position;
  Mat2 error;  //!< predicted − fitted, m/N
};

//! The uncertainty from `training` (the points the model was fitted to) and the model's leave-one-out errors E on
//! them, each held-out point's v taken without it and the per-point fits' variance ν (their slopes' standard
//! errors²) subtracted from E²: interpolation — floor ν, scale the mean of (E² − ν)/v; stationary — floor and
//! scale by least squares of E² − ν on (1, v), both ≥ 0, plus ν. Throws stiffpath::Error naming `source` when
//! there are no leave-one-out errors or fewer than 4 training points.
PredictionUncertainty estimate_uncertainty(const std::vector<PointSamples>& training, const std::vector<LooResidual>& loo,
                                           UncertaintyBasis basis, bool symmetric, const std::string& source);

//! The method's basis: stationary for physical, physical-0, physical-2; interpolation otherwise.
UncertaintyBasis uncertainty_basis(FitMethod method);

//! estimate_uncertainty() with the method's own leave-one-out predictions (compliance::leave_one_out_compliance).
PredictionUncertainty estimate_method_uncertainty(FitMethod method, const std::vector<PointSamples>& points,
                                                  const kinematics::FiveBarGeometry& geometry, const std::string& source);

//! The z of a two-sided 95 % band of a normal error: 1.959964.
inline constexpr double kBand95 = 1.959963984540054;
//! The 97.5 % quantile of Student's t with `dof` degrees of freedom (∞ below 1).
double student_t_975(int dof) noexcept;

}  // namespace stiffpath::compliance
