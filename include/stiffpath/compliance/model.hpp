// The compliance model contract: predict(p, F) → Δ and the 2×2 compliance matrix at p (thesis §4.2).
#pragma once

#include <algorithm>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "stiffpath/core/enum_names.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::compliance {

using kinematics::FitMethod;
using kinematics::Mat2;
using kinematics::Vec2;

//! How far outside its measured rectangle a model may be asked before the `error` policy refuses the
//! point (1 mm, m): a job that only grazes the rectangle's edge is not stopped, one that leaves it is.
inline constexpr double kOutsideMargin_m = 1e-3;

//! What a model does with a point outside the measured grid.
enum class OutsidePolicy {
  clamp,        //!< use the nearest point of the grid's rectangle; callers count such samples
  extrapolate,  //!< extend the model's formula beyond the grid
  error,        //!< refuse (default): callers stop at a point farther than kOutsideMargin_m outside
                //!< the rectangle; within the margin the model clamps
};

//! What the policy does, in words for messages: "refused", "clamped to the region's edge", "extrapolated".
[[nodiscard]] const char* outside_words(OutsidePolicy policy) noexcept;

//! Whether the thesis's zero-force intercepts (n, p, u, w of eq. 4.8) are part of the prediction.
enum class ZeroForce {
  relative,    //!< Δ(p, F) − Δ(p, 0): a robot at rest is not moved (default for compensation)
  thesis_raw,  //!< eqs. 4.7–4.8 as written, intercepts included
};


//! The measured rectangle of a model, in m.
struct GridBounds {
  double x_min = 0.0, x_max = 0.0, y_min = 0.0, y_max = 0.0;
  [[nodiscard]] bool contains(const Vec2& p) const noexcept {
    return p.x() >= x_min && p.x() <= x_max && p.y() >= y_min && p.y() <= y_max;
  }
  [[nodiscard]] Vec2 clamp(const Vec2& p) const noexcept;
  //! The rectangle grown by `margin_m` on every side.
  [[nodiscard]] GridBounds grown(double margin_m) const noexcept {
    return {x_min - margin_m, x_max + margin_m, y_min - margin_m, y_max + margin_m};
  }
  //! The empty rectangle, to be grown point by point with include().
  [[nodiscard]] static constexpr GridBounds none() noexcept { return {1e300, -1e300, 1e300, -1e300}; }
  //! Grows the rectangle to hold p.
  void include(const Vec2& p) noexcept {
    x_min = std::min(x_min, p.x());
    x_max = std::max(x_max, p.x());
    y_min = std::min(y_min, p.y());
    y_max = std::max(y_max, p.y());
  }
};

//! A compliance model of the platform point: Δ = C(p)·F (+ intercepts in thesis_raw mode).
//! Every method is noexcept and allocation-free so that the real-time compensator can call it.
class Model {
 public:
  virtual ~Model() = default;

  //! The method that fitted this model to a displacement table; unset for a model that was not fitted
  //! by one of them (the digital twin's structural truth, a test's field).
  [[nodiscard]] virtual std::optional<FitMethod> method() const noexcept { return std::nullopt; }
  //! What the model is, for messages and figure titles ("physical-spline", "perturbed structural network").
  [[nodiscard]] virtual std::string description() const = 0;
  //! Compliance matrix ∂Δ/∂F at p (m/N), with the outside policy applied (error acts as clamp).
  [[nodiscard]] virtual Mat2 compliance(const Vec2& p) const noexcept = 0;
  //! compliance() at several points in one call (the compensator asks for p and its two neighbours
  //! along the motion every sample); `out` must be at least as long as `points`. The default calls
  //! compliance() per point; a model may share work between the points but gives the same values.
  virtual void compliance_batch(std::span<const Vec2> points, std::span<Mat2> out) const noexcept;
  //! Zero-force deflection at p (m); zero for models without intercepts.
  [[nodiscard]] virtual Vec2 offset(const Vec2& p) const noexcept;
  //! The rectangle where the model was measured.
  [[nodiscard]] virtual GridBounds bounds() const noexcept = 0;

  //! Predicted deflection Δ (m) at p (m) under F (N), eqs. 4.6–4.7.
  [[nodiscard]] Vec2 predict(const Vec2& p, const Vec2& F) const noexcept {
    const Vec2 d = compliance(p) * F;
    return zero_force_ == ZeroForce::thesis_raw ? Vec2(d + offset(p)) : d;
  }
  [[nodiscard]] bool inside(const Vec2& p) const noexcept { return bounds().contains(p); }
  //! Whether the policy refuses p: `error` and p farther than kOutsideMargin_m outside the rectangle.
  [[nodiscard]] bool refuses(const Vec2& p) const noexcept {
    return outside_ == OutsidePolicy::error && !bounds().grown(kOutsideMargin_m).contains(p);
  }

  [[nodiscard]] OutsidePolicy outside_policy() const noexcept { return outside_; }
  //! Virtual so that a model built on another (physical-spline) passes the policy on.
  virtual void set_outside_policy(OutsidePolicy policy) noexcept { outside_ = policy; }
  [[nodiscard]] ZeroForce zero_force() const noexcept { return zero_force_; }
  void set_zero_force(ZeroForce mode) noexcept { zero_force_ = mode; }

 protected:
  //! p after the outside policy: clamped to the bounds unless the policy is extrapolate.
  [[nodiscard]] Vec2 policy_point(const Vec2& p) const noexcept {
    return outside_ == OutsidePolicy::extrapolate ? p : bounds().clamp(p);
  }

 private:
  OutsidePolicy outside_ = OutsidePolicy::error;
  ZeroForce zero_force_ = ZeroForce::relative;
};

}  // namespace stiffpath::compliance

//! Names at the edges: "error", "clamp", "extrapolate".
template <>
struct stiffpath::core::EnumNames<stiffpath::compliance::OutsidePolicy> {
  static constexpr std::string_view what = "outside-region policy";
  static constexpr std::array<std::pair<compliance::OutsidePolicy, std::string_view>, 3> names{
      {{compliance::OutsidePolicy::error, "error"},
       {compliance::OutsidePolicy::clamp, "clamp"},
       {compliance::OutsidePolicy::extrapolate, "extrapolate"}}};
};

//! Names at the edges: "relative", "thesis-raw".
template <>
struct stiffpath::core::EnumNames<stiffpath::compliance::ZeroForce> {
  static constexpr std::string_view what = "zero-force mode";
  static constexpr std::array<std::pair<compliance::ZeroForce, std::string_view>, 2> names{
      {{compliance::ZeroForce::relative, "relative"}, {compliance::ZeroForce::thesis_raw, "thesis-raw"}}};
};
