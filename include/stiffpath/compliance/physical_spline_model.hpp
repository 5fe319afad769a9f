// The physical model plus a thin-plate smoothing spline of what it leaves at the measured points.
#pragma once

#include <array>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/compliance/field_lattice.hpp"
#include "stiffpath/compliance/model.hpp"
#include "stiffpath/compliance/physical_model.hpp"
#include "stiffpath/compliance/point_fit.hpp"

namespace stiffpath::compliance {

//! The smoothing λ of the residual spline (in the spline's unit frame, where the points span 1): small
//! enough that the spline follows the per-point fits to within their noise, large enough to keep its
//! system well conditioned (leave-one-out error on all thesis points: OC 30.8 µm at λ = 10⁻⁴, 32.0 µm at 0.01).
inline constexpr double kResidualSmoothing = 0.01;

//! A thin-plate smoothing spline of a symmetric 2×2 field over scattered points:
//! R(q) = a0 + a1·qx + a2·qy + Σ_k w_k·φ(|q − q_k|), φ(r) = r²·log r, q = (p − origin)/scale,
//! each of (R11, R12 = R21, R22) with its own a and w. It minimises the bending energy among all smooth
//! fields that pass within λ·w_k of the data, so between the points it bends no more than they demand.
struct ResidualSpline {
  Vec2 origin_m = Vec2::Zero();
  double scale_m = 1.0;
  std::vector<Vec2> nodes;                    //!< q_k (unit frame)
  std::vector<std::array<double, 3>> weights;  //!< w_k of (R11, R12, R22), m/N
  std::array<std::array<double, 3>, 3> affine{};  //!< a0, a1, a2 of (R11, R12, R22), m/N
  double smoothing = kResidualSmoothing;
  //! R at p (m/N), symmetric.
  [[nodiscard]] Mat2 at(const Vec2& p) const noexcept;
};

//! Fits the spline to `values` (symmetric parts used) at `positions`. Throws stiffpath::Error naming
//! `source` for fewer than three points, points all on one line, or a system without a finite solution.
ResidualSpline fit_residual_spline(const std::vector<Vec2>& positions, const std::vector<Mat2>& values,
                                   double smoothing, const std::string& source);

//! C(p) = C_phys(p) + R(p): the five-bar's statics (the `physical` model, order 1) carry the field's shape
//! toward the singularities; the spline R of its residual at the measured points (the per-point fits of
//! eq. 4.8 minus C_phys there) carries what a low-order D(p) cannot. Symmetric by construction. Between
//! the points R bends as little as the points allow; outside them it continues linearly (extrapolate) or
//! is held at the rectangle's edge (clamp, error), while C_phys keeps its own policy (D held, U exact).
//! Inside the measured rectangle C is read from a Catmull–Rom lattice (FieldLattice) filled at
//! construction, so the real-time step costs what the bilinear model costs; elsewhere it is evaluated.
class PhysicalSplineModel final : public Model {
 public:
  PhysicalSplineModel(std::unique_ptr<PhysicalModel> base, ResidualSpline residual, nlohmann::json stats,
                      bool tabulate = true);

  [[nodiscard]] std::optional<FitMethod> method() const noexcept override { return FitMethod::physical_spline; }
  [[nodiscard]] std::string description() const override { return "physical-spline"; }
  [[nodiscard]] Mat2 compliance(const Vec2& p) const noexcept override;
  [[nodiscard]] GridBounds bounds() const noexcept override { return base_->bounds(); }
  //! Its parameters and fit statistics as JSON, as model files hold them (compliance::model_parameters).
  [[nodiscard]] nlohmann::json parameters() const;
  void set_outside_policy(OutsidePolicy policy) noexcept override;

  //! C evaluated without the lattice.
  [[nodiscard]] Mat2 exact(const Vec2& p) const noexcept;
  [[nodiscard]] const PhysicalModel& physical() const noexcept { return *base_; }
  [[nodiscard]] const ResidualSpline& residual() const noexcept { return residual_; }
  //! The lattice (null when the model was made without one).
  [[nodiscard]] const FieldLattice* lattice() const noexcept { return lattice_ ? &*lattice_ : nullptr; }

 private:
  std::unique_ptr<PhysicalModel> base_;
  ResidualSpline residual_;
  nlohmann::json stats_;
  std::optional<FieldLattice> lattice_;
};

//! The physical model (order 1) fitted to every sample, then the spline of the per-point fits' residual.
//! `tabulate` = false skips the lattice (cross-validation's refits predict one point each).
std::unique_ptr<PhysicalSplineModel> fit_physical_spline_model(const std::vector<PointSamples>& points,
                                                               const kinematics::FiveBarGeometry& geometry,
                                                               const std::string& source, bool tabulate = true);

}  // namespace stiffpath::compliance
