// A compliance model with a smooth correction learned from the robot's own marks (calibration): C' = S(p)·C(p)·S(p).
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <memory>

#include "stiffpath/compliance/model.hpp"

namespace stiffpath::compliance {

//! The smooth correction: the symmetric S(p) = [√sx(p) k(p); k(p) √sy(p)] with sx, sy and k linear in the normalised
//! coordinates x̂ = (x − origin_x)/half_size_x, ŷ likewise: s = c0 + c1·x̂ + c2·ŷ. S·C·S stays symmetric positive
//! definite wherever S is invertible (sx, sy > 0 and √(sx·sy) > k²). With k = 0 it scales the deflection along x by
//! sx and along y by sy (the cross terms by √(sx·sy)); k turns the field's principal directions, which a change of
//! the structure (another link, a joint stiffer than the model says) does and a scale alone cannot.
struct ComplianceCorrection {
  Vec2 origin_m = Vec2::Zero();
  Vec2 half_size_m = Vec2::Ones();    //!< > 0
  std::array<double, 3> sx{1.0, 0.0, 0.0};
  std::array<double, 3> sy{1.0, 0.0, 0.0};
  std::array<double, 3> sxy{0.0, 0.0, 0.0};  //!< k, S's off-diagonal

  //! sx and sy at p (not clamped).
  [[nodiscard]] Vec2 factors(const Vec2& p) const noexcept;
  //! S at p (sx, sy floored at 10⁻¹²).
  [[nodiscard]] Mat2 matrix(const Vec2& p) const noexcept;
  //! The identity correction.
  [[nodiscard]] bool identity() const noexcept;
};

//! `base` with `correction` applied: compliance(p) = S(p)·C_base(p)·S(p), evaluated at the base's policy point.
class CorrectedModel final : public Model {
 public:
  //! Throws stiffpath::Error when S is not invertible somewhere on the base's rectangle or a half size is not
  //! positive. Checking the corners suffices: sx, sy are linear, so det S = √(sx·sy) − k² is concave there.
  CorrectedModel(std::shared_ptr<Model> base, ComplianceCorrection correction);

  [[nodiscard]] std::optional<FitMethod> method() const noexcept override { return base_->method(); }
  [[nodiscard]] std::string description() const override { return base_->description() + " corrected by a calibration plate"; }
  [[nodiscard]] Mat2 compliance(const Vec2& p) const noexcept override;
  void compliance_batch(std::span<const Vec2> points, std::span<Mat2> out) const noexcept override;
  [[nodiscard]] Vec2 offset(const Vec2& p) const noexcept override { return base_->offset(p); }
  [[nodiscard]] GridBounds bounds() const noexcept override { return base_->bounds(); }
  //! Its parameters and fit statistics as JSON, as model files hold them (compliance::model_parameters).
  [[nodiscard]] nlohmann::json parameters() const;
  void set_outside_policy(OutsidePolicy policy) noexcept override;

  [[nodiscard]] const Model& base() const noexcept { return *base_; }
  [[nodiscard]] const ComplianceCorrection& correction() const noexcept { return correction_; }

 private:
  [[nodiscard]] Mat2 corrected(const Vec2& p, const Mat2& C) const noexcept;

  std::shared_ptr<Model> base_;
  ComplianceCorrection correction_;
};

}  // namespace stiffpath::compliance
