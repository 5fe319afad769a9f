// Physics-based compliance from the five-bar's statics (virtual joint method in link-force coordinates).
#pragma once

#include <array>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/kinematics/five_bar.hpp"

namespace stiffpath::compliance {

//! A force F at C splits into the axial forces of the two distal links (pin-jointed two-force
//! members): F = f_1·u_1 + f_2·u_2 with u_i the unit vector from elbow B_i to C, i.e. f = U⁻¹F,
//! U = [u_1 u_2] (for the thesis robot u_1 = (cos θ2, sin θ2), u_2 = (cos θ1, sin θ1)). Each chain's
//! compliance (actuator torsion, proximal-link bending and stretch, distal-link stretch — see
//! docs/compliance.md for the derivation) acts on its link force, and the platform moves by
//! Δ = U⁻ᵀ D U⁻¹ F. So C(p) = U(p)⁻ᵀ D(p) U(p)⁻¹ with D symmetric 2×2 (D11: the left chain, D22: the
//! right chain, D12: their coupling through the base and the platform). U carries the robot's own
//! geometry (in its working mode), so C grows correctly toward the serial and parallel singularities
//! where U or the chains degenerate; D varies slowly and is a low-order polynomial in (x, y) whose
//! coefficients are fitted by linear least squares to every measurement at once. C is symmetric
//! (reciprocity) by construction and positive definite wherever D is.
class PhysicalModel final : public Model {
 public:
  static constexpr int kMaxTerms = 6;

  //! `coefficients[k]` = (D11, D12, D22) of basis term k in m/N; order 0, 1 or 2 → 1, 3 or 6 terms.
  PhysicalModel(const kinematics::FiveBarGeometry& geometry, GridBounds bounds, int order,
                std::vector<std::array<double, 3>> coefficients, nlohmann::json stats);

  [[nodiscard]] std::optional<FitMethod> method() const noexcept override {
    return order_ == 0 ? FitMethod::physical_0 : order_ == 2 ? FitMethod::physical_2 : FitMethod::physical;
  }
  [[nodiscard]] std::string description() const override { return std::string(core::enum_name(*method())); }
  //! U⁻ᵀ D U⁻¹ at p. The outside policy applies to D's polynomial (clamp: D is held at its edge
  //! value); the geometric factor U always uses the true p, so growth toward singularity is kept.
  [[nodiscard]] Mat2 compliance(const Vec2& p) const noexcept override;
  [[nodiscard]] GridBounds bounds() const noexcept override { return bounds_; }
  //! Its parameters and fit statistics as JSON, as model files hold them (compliance::model_parameters).
  [[nodiscard]] nlohmann::json parameters() const;

  //! D(p) in m/N (for the positive-definiteness check and plots).
  [[nodiscard]] Mat2 link_compliance(const Vec2& p) const noexcept;
  [[nodiscard]] int order() const noexcept { return order_; }
  [[nodiscard]] const kinematics::FiveBarGeometry& geometry() const noexcept { return geometry_; }

  //! Polynomial basis of the given order at p, normalised to [−1, 1] over `bounds`; returns the count.
  static int basis(const GridBounds& bounds, int order, const Vec2& p, std::array<double, kMaxTerms>& out) noexcept;
  //! U⁻¹ at p (rows: the maps from F to the left and right distal links' forces), from the geometry's
  //! inverse kinematics in its working mode without the singularity margins: the distances |A_iC| are
  //! kept just inside the arms' reach so that the map stays finite. The thesis's geometry uses eq. 2.2.
  static Mat2 link_force_map(const kinematics::FiveBarGeometry& geometry, const Vec2& p) noexcept;

 private:
  kinematics::FiveBarGeometry geometry_;
  bool thesis_ = false;  // eq. 2.2's closed form for U
  GridBounds bounds_;
  int order_;
  std::vector<std::array<double, 3>> coefficients_;
  nlohmann::json stats_;
};

//! Fits D's coefficients to all samples (relative form: Δ = C(p)·F) by linear least squares.
//! Throws stiffpath::Error naming `source` when there are fewer equations than unknowns. `check_definite` = false
//! skips the 51 × 51 check of D's positive definiteness (its stats then lack it): for leave-one-out refits.
std::unique_ptr<PhysicalModel> fit_physical_model(const std::vector<PointSamples>& points,
                                                  const kinematics::FiveBarGeometry& geometry, int order,
                                                  const std::string& source, bool check_definite = true);

}  // namespace stiffpath::compliance
