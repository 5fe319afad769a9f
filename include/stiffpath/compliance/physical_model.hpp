// Physics-based compliance from the five-bar's statics (virtual joint method in link-force coordinates).
#pragma once

#include <array>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/compliance/point_fit.hpp"

namespace stiffpath::compliance {

//! A force F at C splits into the axial forces of the two distal links (two-force members):
//! F = f_AC·w2 + f_BC·w1 with w_i = (cos θi, sin θi), i.e. f = U⁻¹F, U = [w2 w1]. Each chain's
//! compliance (actuator torsion, proximal-link bending and stretch, distal-link stretch — see
//! docs/compliance.md for the derivation) acts on its link force, and the platform moves by
//! Δ = U⁻ᵀ D U⁻¹ F. So C(p) = U(p)⁻ᵀ D(p) U(p)⁻¹ with D symmetric 2×2 (D11: chain A0–A–C,
//! D22: chain A0–B–C, D12: their coupling through the base and the platform). U carries the
//! geometry, so C grows correctly toward the stretched-out boundary where U becomes singular;
//! D varies slowly and is a low-order polynomial in (x, y) whose coefficients are fitted by linear
//! least squares to every measurement at once. C is symmetric (reciprocity) by construction and
//! positive definite wherever D is.
class PhysicalModel final : public Model {
 public:
  static constexpr int kMaxTerms = 6;

  //! `coefficients[k]` = (D11, D12, D22) of basis term k in m/N; order 0, 1 or 2 → 1, 3 or 6 terms.
  PhysicalModel(double link_length_m, GridBounds bounds, int order, std::vector<std::array<double, 3>> coefficients,
                nlohmann::json stats);

  [[nodiscard]] std::string method() const override { return "physical"; }
  //! U⁻ᵀ D U⁻¹ at p. The outside policy applies to D's polynomial (clamp: D is held at its edge
  //! value); the geometric factor U always uses the true p, so growth toward singularity is kept.
  [[nodiscard]] Mat2 compliance(const Vec2& p) const noexcept override;
  [[nodiscard]] GridBounds bounds() const noexcept override { return bounds_; }
  [[nodiscard]] nlohmann::json parameters() const override;

  //! D(p) in m/N (for the positive-definiteness check and plots).
  [[nodiscard]] Mat2 link_compliance(const Vec2& p) const noexcept;
  [[nodiscard]] int order() const noexcept { return order_; }
  [[nodiscard]] double link_length() const noexcept { return l_; }

  //! Polynomial basis of the given order at p, normalised to [−1, 1] over `bounds`; returns the count.
  static int basis(const GridBounds& bounds, int order, const Vec2& p, std::array<double, kMaxTerms>& out) noexcept;
  //! U⁻¹ at p for links of length l (rows: the maps from F to f_AC and f_BC).
  static Mat2 link_force_map(double link_length_m, const Vec2& p) noexcept;

 private:
  double l_;
  GridBounds bounds_;
  int order_;
  std::vector<std::array<double, 3>> coefficients_;
  nlohmann::json stats_;
};

//! Fits D's coefficients to all samples (relative form: Δ = C(p)·F) by linear least squares.
//! Throws stiffpath::Error naming `source` when there are fewer equations than unknowns.
std::unique_ptr<PhysicalModel> fit_physical_model(const std::vector<PointSamples>& points, double link_length_m,
                                                  int order, const std::string& source);

}  // namespace stiffpath::compliance
