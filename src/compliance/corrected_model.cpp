// CorrectedModel: a base compliance model corrected by the calibration's smooth symmetric field S(p), C' = S·C·S.
#include "stiffpath/compliance/corrected_model.hpp"

#include <Eigen/LU>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

Vec2 ComplianceCorrection::factors(const Vec2& p) const noexcept {
  const double u = (p.x() - origin_m.x()) / half_size_m.x(), v = (p.y() - origin_m.y()) / half_size_m.y();
  return {sx[0] + sx[1] * u + sx[2] * v, sy[0] + sy[1] * u + sy[2] * v};
}

Mat2 ComplianceCorrection::matrix(const Vec2& p) const noexcept {
  const Vec2 s = factors(p).cwiseMax(1e-12).cwiseSqrt();
  const double u = (p.x() - origin_m.x()) / half_size_m.x(), v = (p.y() - origin_m.y()) / half_size_m.y();
  const double k = sxy[0] + sxy[1] * u + sxy[2] * v;
  Mat2 S;
  S << s.x(), k, k, s.y();
  return S;
}

bool ComplianceCorrection::identity() const noexcept {
  constexpr std::array<double, 3> one{1.0, 0.0, 0.0}, zero{0.0, 0.0, 0.0};
  return sx == one && sy == one && sxy == zero;
}

CorrectedModel::CorrectedModel(std::shared_ptr<Model> base, ComplianceCorrection correction)
    : base_(std::move(base)), correction_(correction) {
  if (!base_) throw Error("corrected compliance model: no base model");
  if (!(correction_.half_size_m.x() > 0.0 && correction_.half_size_m.y() > 0.0) || !correction_.origin_m.allFinite()) {
    throw Error("compliance correction: the half sizes must be positive and the origin finite");
  }
  const GridBounds b = base_->bounds();
  for (const Vec2& corner : {Vec2(b.x_min, b.y_min), Vec2(b.x_max, b.y_min), Vec2(b.x_min, b.y_max), Vec2(b.x_max, b.y_max)}) {
    const Vec2 s = correction_.factors(corner);
    const Mat2 S = correction_.matrix(corner);
    if (!(s.x() > 0.0 && s.y() > 0.0) || !s.allFinite() || !S.allFinite() || !(S.determinant() > 1e-9)) {
      throw Error(fmt::format("compliance correction: its factors ({:g}, {:g}, cross term {:g}) at ({:.1f}, {:.1f}) mm "
                              "make S singular: C would not stay positive definite",
                              s.x(), s.y(), S(0, 1), corner.x() * 1e3, corner.y() * 1e3));
    }
  }
  Model::set_outside_policy(base_->outside_policy());
  set_zero_force(base_->zero_force());
}

Mat2 CorrectedModel::corrected(const Vec2& p, const Mat2& C) const noexcept {
  const Mat2 S = correction_.matrix(policy_point(p));
  return S * C * S;
}

Mat2 CorrectedModel::compliance(const Vec2& p) const noexcept { return corrected(p, base_->compliance(p)); }

void CorrectedModel::compliance_batch(std::span<const Vec2> points, std::span<Mat2> out) const noexcept {
  base_->compliance_batch(points, out);
  for (std::size_t k = 0; k < points.size(); ++k) out[k] = corrected(points[k], out[k]);
}

void CorrectedModel::set_outside_policy(OutsidePolicy policy) noexcept {
  Model::set_outside_policy(policy);
  base_->set_outside_policy(policy);
}

nlohmann::json CorrectedModel::parameters() const {
  nlohmann::json out = model_parameters(*base_);
  const auto& c = correction_;
  out["correction"] = {{"origin_mm", {c.origin_m.x() * 1e3, c.origin_m.y() * 1e3}},
                       {"half_size_mm", {c.half_size_m.x() * 1e3, c.half_size_m.y() * 1e3}},
                       {"sx", {c.sx[0], c.sx[1], c.sx[2]}},
                       {"sy", {c.sy[0], c.sy[1], c.sy[2]}},
                       {"sxy", {c.sxy[0], c.sxy[1], c.sxy[2]}}};
  return out;
}

}  // namespace stiffpath::compliance
