// The plant of the digital twin: joint servos, rigid five-bar kinematics and the compliant tip on a spring-damper.
#pragma once

#include <Eigen/LU>
#include <memory>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/five_bar.hpp"

namespace stiffpath::simulation {

using kinematics::Mat2;
using kinematics::Vec2;

//! Settings of the plant. Documented defaults (see docs/simulation.md for the reasoning).
struct PlantOptions {
  //! Integration rate (Hz): 10× the 2 kHz command rate, and ~200 steps per period of the stiffest
  //! tip mode (~100 Hz), so the symplectic Euler step's frequency error is below 0.01 %.
  double step_rate_hz = 20000.0;
  //! Bandwidth f_s of the joints' position loops (Hz), ω_s = 2π·f_s. 100 Hz is a typical stiff
  //! direct-drive servo; it only acts on the error, because the drives feed the commanded velocity
  //! and acceleration forward (what `stiffpath run` sends), as industrial drives do.
  double servo_bandwidth_hz = 100.0;
  double servo_damping = 1.0;  //!< damping ratio of the position loop (critically damped: no overshoot)
  //! Damping ratio ζ of the tip's modes. Bolted, bearing-jointed metal structures show 1–5 %; the
  //! thesis's marks (fig. 4.12) show vibration dying out within a few periods, so 5 %.
  double tip_damping_ratio = 0.05;
};

//! Reference of the joints at one instant: angle, velocity and acceleration (SI).
struct JointReference {
  Vec2 q_rad = Vec2::Zero();
  Vec2 qd_rad_s = Vec2::Zero();
  Vec2 qdd_rad_s2 = Vec2::Zero();
};

//! State of the plant (SI).
struct PlantState {
  Vec2 q_rad = Vec2::Zero();         //!< actual joint angles
  Vec2 qd_rad_s = Vec2::Zero();      //!< actual joint velocities
  Vec2 tip_m = Vec2::Zero();         //!< position of the platform mass (the tool point)
  Vec2 tip_m_s = Vec2::Zero();       //!< its velocity
};

//! The robot:
//!  - servos: q̈ = q̈_ref + ω_s²(q_ref − q) + 2ζ_sω_s(q̇_ref − q̇) per joint (feed-forward position loop);
//!  - base point p_b = FK(q) (eq. 2.1), ṗ_b = J(q)q̇: the rigid mechanism's idea of the platform;
//!  - tip: m·p̈ = −K(p_b)(p − p_b) − D(p_b)(ṗ − ṗ_b) + F_ext with K = C_true⁻¹ and the modal damping
//!    D = 2ζ√m·K^{1/2} (each eigen-mode of K gets the damping ratio ζ: c_i = 2ζ√(k_i m)).
//! Under the D'Alembert force −m·a the static deflection p − p_b = C·(−m·a), the sign of compensation's
//! Δ = C·F. The load does not feed back into the servos: C_true was measured with the drives holding
//! position, so their stiffness is already part of it. Integrated by symplectic (semi-implicit) Euler,
//! which keeps the undamped oscillator's energy bounded (no artificial growth or decay).
class Plant {
 public:
  //! `truth` is C_true (m/N), `mass_kg` > 0 the moving mass. Throws stiffpath::Error for bad options.
  Plant(const kinematics::FiveBar& robot, std::shared_ptr<const compliance::Model> truth, double mass_kg,
        PlantOptions options = {});

  //! Puts the joints at q, q̇ and the tip at the base point, moving with it, undeflected.
  void reset(const Vec2& q_rad, const Vec2& qd_rad_s = Vec2::Zero()) noexcept;
  //! Advances by dt (s) towards the reference, with an optional external force on the tip (N).
  void step(const JointReference& reference, double dt_s, const Vec2& external_force_N = Vec2::Zero()) noexcept;

  [[nodiscard]] const PlantState& state() const noexcept { return state_; }
  void set_state(const PlantState& state) noexcept { state_ = state; }
  [[nodiscard]] Vec2 base() const noexcept { return robot_.forward(state_.q_rad); }
  [[nodiscard]] Vec2 base_velocity() const noexcept { return robot_.jacobian(state_.q_rad) * state_.qd_rad_s; }
  //! K(p) = C_true(p)⁻¹ (N/m).
  [[nodiscard]] Mat2 stiffness(const Vec2& p) const noexcept;
  //! D(p) = 2ζ√m·K(p)^{1/2} (N·s/m).
  [[nodiscard]] Mat2 damping(const Vec2& p) const noexcept;
  //! Kinetic energy of the tip relative to the base plus the spring's energy (J), for tests.
  [[nodiscard]] double relative_energy() const noexcept;
  [[nodiscard]] double mass() const noexcept { return mass_; }
  [[nodiscard]] const PlantOptions& options() const noexcept { return options_; }

 private:
  kinematics::FiveBar robot_;
  std::shared_ptr<const compliance::Model> truth_;
  double mass_;
  PlantOptions options_;
  double omega_s_;
  PlantState state_;
};

//! The symmetric square root of a symmetric positive definite 2×2 matrix (closed form:
//! √A = (A + √det A·I)/√(tr A + 2√det A)).
Mat2 sqrt_spd(const Mat2& A) noexcept;

}  // namespace stiffpath::simulation
