// The real-time compensation step (thesis fig. 4.3) that a controller embeds in its 2 kHz loop.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "stiffpath/compensation/samples.hpp"
#include "stiffpath/core/enum_names.hpp"
#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::compensation {

//! How the deflection to correct is predicted.
enum class Method : std::uint8_t {
  //! The thesis's correction (fig. 4.3): the static deflection Δ = C(p)·F under F = −m·a (eqs. 4.4–4.7).
  quasi_static,
  //! Dynamic inversion of the tip model m·p̈ = −K(p − p_b) − D(ṗ − ṗ_b), K = C⁻¹, D = 2ζ√m·K^{1/2}:
  //! the base offset δ = p_b − p that makes the tip follow the plan obeys δ + T·δ̇ = C·m·a with
  //! T = C·D; its particular solution δ = δ₀ − T·δ̇₀ + T²·δ̈₀ (δ₀ = C·m·a) is exact wherever the
  //! snap is constant (constant C).
  dynamic,
};


//! Settings of the compensation (documented defaults).
struct CompensatorOptions {
  double gain = 1.0;          //!< k in p_cmd = p − k·Δ; 0 turns compensation off (thesis §4.7 suggests < 1 may suit some builds)
  bool enabled = true;        //!< false: p_cmd = p (the "without compensation" runs)
  bool check_limits = true;   //!< check reach and joint limits on every sample
  Method method = Method::dynamic;  //!< as every surface's default (job::JobSpec); the thesis's: quasi_static
  //! ζ of the tip's modes assumed by Method::dynamic, finite, 0…2. Unset: the robot's tip_damping_ratio
  //! (its robot file's, 0.05 when the file gives none: bolted, bearing-jointed metal structures show
  //! 1–5 %, the thesis's marks, fig. 4.12, die out within a few periods). options() holds the value used.
  std::optional<double> damping_ratio;
};

//! For each planned sample (fig. 4.3):
//!   1. F = −m·a, the D'Alembert force of the platform mass at its CG (eq. 4.4);
//!   2. Δ = C(p)·F from the compliance model (eqs. 4.6–4.7, relative to zero force by default);
//!   3. p_cmd = p − k·Δ (Method::quasi_static), or p_cmd = p + k·δ with the dynamic offset δ
//!      (Method::dynamic; `deflection_m` then holds −δ, the tip's predicted lag behind the base);
//!   4. θ = IK(p_cmd) (eq. 2.2 for the thesis robot, the general five-bar otherwise), ω = J⁻¹ṗ_cmd,
//!      α = J⁻¹(p̈_cmd − J̇ω);
//!   5. reach and joint-limit checks; a sample farther than compliance::kOutsideMargin_m outside the
//!      model's measured rectangle is refused when the model's policy is `error` (the default).
//! The commanded velocity and acceleration include the correction's own rates,
//! ṗ_cmd = ṗ + k·m·(C·j + Ċ·a) and p̈_cmd = p̈ + k·m·(C·s + 2·Ċ·j + C̈·a), with Ċ, C̈ the model's
//! rates of change along the local motion (central differences of C at p ± v·h + a·h²/2, points
//! ~0.1 mm apart) and s the snap (zero inside jerk-limited phases). Method::dynamic adds −T·δ̇₀ + T²·δ̈₀
//! to the offset and the matching terms to its rates (δ⃛₀ ≈ m·(3·C̈·j + 3·Ċ·s), crackle taken as 0).
//! `load_torque_Nm` = Jᵀ·m·a is the torque the tip's spring and damper put on the drives when the tip
//! follows the plan: a drive that adds it as torque feed-forward does not lag under the load.
//! step() is noexcept, does not allocate, lock or throw, takes constant time (one call for the
//! model at three points, one IK), and every field of its result is finite for any input.
class Compensator {
 public:
  //! Keeps the model alive; throws stiffpath::Error for a non-finite or negative gain, a damping ratio
  //! outside 0…2, or a null model
  //! when compensating (without compensation a robot with no compliance data yet may pass none: the
  //! predicted deflection is then zero and nothing is outside).
  Compensator(const kinematics::Robot& robot, std::shared_ptr<const compliance::Model> model,
              CompensatorOptions options = {});

  [[nodiscard]] JointCommand step(const TaskSample& sample) const noexcept;

  [[nodiscard]] const CompensatorOptions& options() const noexcept { return options_; }
  [[nodiscard]] const kinematics::Robot& robot() const noexcept { return spec_; }
  [[nodiscard]] const kinematics::FiveBar& five_bar() const noexcept { return five_bar_; }
  //! The model; only when one was given (see the constructor).
  [[nodiscard]] const compliance::Model& model() const noexcept { return *model_; }
  [[nodiscard]] bool has_model() const noexcept { return model_ != nullptr; }

 private:
  // step() in three parts (smaller functions than one whole step: measured 17 % faster, same numbers).
  // Where the model is asked for C: p, and its neighbours along the motion p ± v·h + a·h²/2.
  struct Lookup {
    std::array<Vec2, 3> points;
    double inverse_h = 0.0;  // 1/h, so that the differences take no division
    std::size_t count = 0;   // 3 when compensating, 1 (p only) when not
  };
  //! Checks the sample, fills what needs no model (force, flags) and the points; false: `c` is refused.
  bool prepare(const TaskSample& s, JointCommand& c, Lookup& lookup) const noexcept;
  //! C at the points (zero without a model).
  void look_up(std::span<const Vec2> points, std::span<Mat2> Cs) const noexcept;
  //! Deflection, corrected target and its rates, inverse kinematics, joint checks.
  void finish(const TaskSample& s, const Lookup& lookup, const std::array<Mat2, 3>& Cs, JointCommand& c) const noexcept;

  kinematics::Robot spec_;
  kinematics::FiveBar five_bar_;
  std::shared_ptr<const compliance::Model> model_;
  CompensatorOptions options_;
  double effective_gain_;
  compliance::GridBounds bounds_;   // the model's rectangle, asked once (a model's bounds never change)
  compliance::GridBounds allowed_;  // … grown by the margin: beyond it the `error` policy refuses
};

}  // namespace stiffpath::compensation

//! Names at the edges: "quasi-static", "dynamic".
template <>
struct stiffpath::core::EnumNames<stiffpath::compensation::Method> {
  static constexpr std::string_view what = "compensation method";
  static constexpr std::array<std::pair<compensation::Method, std::string_view>, 2> names{
      {{compensation::Method::dynamic, "dynamic"}, {compensation::Method::quasi_static, "quasi-static"}}};
};
