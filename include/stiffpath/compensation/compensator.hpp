// The real-time compensation step (thesis fig. 4.3) that a controller embeds in its 2 kHz loop.
#pragma once

#include <memory>

#include "stiffpath/compensation/samples.hpp"
#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::compensation {

//! Settings of the compensation (documented defaults).
struct CompensatorOptions {
  double gain = 1.0;          //!< k in p_cmd = p − k·Δ; 0 turns compensation off (thesis §4.7 suggests < 1 may suit some builds)
  bool enabled = true;        //!< false: p_cmd = p (the "without compensation" runs)
  bool check_limits = true;   //!< check reach and joint limits on every sample
};

//! For each planned sample (fig. 4.3):
//!   1. F = −m·a, the D'Alembert force of the platform mass at its CG (eq. 4.4);
//!   2. Δ = C(p)·F from the compliance model (eqs. 4.6–4.7, relative to zero force by default);
//!   3. p_cmd = p − k·Δ;
//!   4. θ = IK(p_cmd) (eq. 2.2 for the thesis robot, the general five-bar otherwise), ω = J⁻¹ṗ_cmd,
//!      α = J⁻¹(p̈_cmd − J̇ω);
//!   5. reach and joint-limit checks; a sample farther than compliance::kOutsideMargin_m outside the
//!      model's measured rectangle is refused when the model's policy is `error` (the default).
//! The commanded velocity and acceleration include the correction's own rates,
//! ṗ_cmd = ṗ + k·m·(C·j + Ċ·a) and p̈_cmd = p̈ + k·m·(C·s + 2·Ċ·j + C̈·a), with Ċ, C̈ the model's
//! rates of change along the local motion (central differences of C at p ± v·h + a·h²/2, points
//! ~0.1 mm apart) and s the snap (zero inside jerk-limited phases). step() is noexcept, does not
//! allocate, lock or throw, and takes constant time (one call for the model at three points, one IK).
class Compensator {
 public:
  //! Keeps the model alive; throws stiffpath::Error for a non-finite or negative gain, or a null model
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
  kinematics::Robot spec_;
  kinematics::FiveBar five_bar_;
  std::shared_ptr<const compliance::Model> model_;
  CompensatorOptions options_;
  double effective_gain_;
  compliance::GridBounds bounds_;   // the model's rectangle, asked once (a model's bounds never change)
  compliance::GridBounds allowed_;  // … grown by the margin: beyond it the `error` policy refuses
};

}  // namespace stiffpath::compensation
