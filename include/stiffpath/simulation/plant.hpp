// The plant of the digital twin: joint servos, rigid five-bar kinematics and the compliant tip on a spring-damper.
#pragma once

#include <Eigen/LU>
#include <memory>
#include <optional>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/five_bar.hpp"

namespace stiffpath::simulation {

using kinematics::Mat2;
using kinematics::Vec2;

//! Settings of the plant. Documented defaults (see docs/simulation.md for the reasoning).
//! ζ of a plant built without a robot's own value.
inline constexpr double kDefaultTipDampingRatio = 0.05;

struct PlantOptions {
  //! Integration rate (Hz): 10× the 2 kHz command rate, and ~200 steps per period of the stiffest
  //! tip mode (~100 Hz), so the symplectic Euler step's frequency error is below 0.01 %.
  double step_rate_hz = 20000.0;
  //! Bandwidth f_s of the joints' closed position loops (Hz), ω_s = 2π·f_s, with the loop's damping ζ_s:
  //! the drive's velocity loop has the gain K_v = 2ζ_s·ω_s·J_tune (J_tune: the inertia the drive was tuned
  //! for, below) and its position loop K_p = ω_s/(2ζ_s), i.e. a 200 Hz velocity and a 50 Hz position loop
  //! for the defaults, typical of the AC servo drives on such robots. Unloaded, q̈ = q̈_ref + ω_s²(q_ref − q)
  //! + 2ζ_sω_s(q̇_ref − q̇).
  double servo_bandwidth_hz = 100.0;
  double servo_damping = 1.0;  //!< ζ_s of the position loop (critically damped: no overshoot)
  //! Inertia of motor, reducer and proximal link reflected at each joint (kg·m²): a ~400 W AC servo rotor
  //! (≈ 3·10⁻⁵ kg·m²) behind a 10:1 reducer, plus its share of the links. It moves rigidly with the joint;
  //! the platform's mass hangs on the compliant tip and loads the joint through Jᵀ.
  double motor_inertia_kg_m2 = 0.01;
  //! Fraction κ of the rigid-body torque feed-forward τ_ff = J_m·q̈_ref + κ·Jᵀm_ff(J·q̈_ref + J̇·q̇_ref) at the
  //! reference, with the controller's nominal mass m_ff: a robot controller's model-based feed-forward.
  //! 0 = the drive feeds forward only its own inertia.
  double load_feedforward = 1.0;
  //! Where the load part of that feed-forward comes from. false: the rigid-body model at the reference,
  //! κ·Jᵀm_ff·ẍ_ref, as a robot controller computes it from the joint commands. true: the command's own
  //! D'Alembert force, κ·Jᵀ·(−F) with F = −m·a of the planned motion (what the compensator writes as
  //! fx_n, fy_n and as `load_torque_Nm`): with compensation the corrected command accelerates by the
  //! offset's δ̈ more than the tip does, and the rigid-body model feeds that forward as a load the drives
  //! never feel (an estimate at 5 g with 8 ms smoothing: C ≈ 2 µm/N, m = 3.6 kg, snap up to 2j/W ≈ 4.9·10⁶ m/s⁴
  //! give δ̈ ≈ 35 m/s², comparable to a = 49 m/s²).
  bool load_feedforward_from_command = false;
  //! The mass the controller believes (feed-forward and loop tuning), kg; 0 = the plant's mass.
  double controller_mass_kg = 0.0;
  //! Damping ratio ζ of the tip's modes. Unset: the robot's tip_damping_ratio when simulate() builds the
  //! plant, else kDefaultTipDampingRatio (bolted, bearing-jointed metal structures show 1–5 %; the
  //! thesis's marks, fig. 4.12, show vibration dying out within a few periods, so 5 %).
  std::optional<double> tip_damping_ratio;
  //! Whether the joints feel the tip's spring and damper (τ_load = Jᵀ·F). Off: the servos track as if unloaded
  //! (the ideal servo of the error budget).
  bool servo_feels_load = true;
};

//! Reference of the joints at one instant: angle, velocity and acceleration (SI).
struct JointReference {
  Vec2 q_rad = Vec2::Zero();
  Vec2 qd_rad_s = Vec2::Zero();
  Vec2 qdd_rad_s2 = Vec2::Zero();
  //! m·a the tip's spring and damper must carry for the planned motion (N): −F of the command; used by
  //! PlantOptions::load_feedforward_from_command.
  Vec2 load_force_N = Vec2::Zero();
};

//! State of the plant (SI).
struct PlantState {
  Vec2 q_rad = Vec2::Zero();         //!< actual joint angles
  Vec2 qd_rad_s = Vec2::Zero();      //!< actual joint velocities
  Vec2 tip_m = Vec2::Zero();         //!< position of the platform mass (the tool point)
  Vec2 tip_m_s = Vec2::Zero();       //!< its velocity
};

//! The robot:
//!  - joints (drive + motor): J_m·q̈ = τ_ff + K_v(q̇_ref + K_p(q_ref − q) − q̇) + Jᵀ(q)·F_tip, a cascaded P/P drive
//!    with the feed-forward τ_ff of PlantOptions and the load F_tip = K(p − p_b) + D(ṗ − ṗ_b) that the
//!    platform's spring and damper put on the end point (the velocity loop integrated implicitly);
//!  - base point p_b = FK(q) (eq. 2.1), ṗ_b = J(q)q̇: the rigid mechanism's idea of the platform;
//!  - tip: m·p̈ = −K(p_b)(p − p_b) − D(p_b)(ṗ − ṗ_b) + F_ext with K = (C_true + L)⁻¹, L the CG lever
//!    (make_cg_lever: the inertial force acts at the CG, h above G, and tilts the platform), and the modal
//!    damping D = 2ζ√m·K_s^{1/2} (K_s the symmetric part of K; each mode gets c_i = 2ζ√(k_i m)).
//! Under the D'Alembert force −m·a the static deflection p − p_b = C·(−m·a), the sign of compensation's
//! Δ = C·F. Integrated by symplectic (semi-implicit) Euler, which keeps the undamped oscillator's energy
//! bounded (no artificial growth or decay). O(1) per step, no allocation.
class Plant {
 public:
  //! `truth` is C_true (m/N), `mass_kg` > 0 the moving mass. Throws stiffpath::Error for bad options.
  //! `cg_lever` (may be null) is added to C_true for the inertial load.
  Plant(const kinematics::FiveBar& robot, std::shared_ptr<const compliance::Model> truth, double mass_kg,
        PlantOptions options = {}, std::shared_ptr<const compliance::Model> cg_lever = nullptr);

  //! Puts the joints at q, q̇ and the tip at the base point, moving with it, undeflected.
  void reset(const Vec2& q_rad, const Vec2& qd_rad_s = Vec2::Zero()) noexcept;
  //! Advances by dt (s) towards the reference, with an optional external force on the tip (N).
  void step(const JointReference& reference, double dt_s, const Vec2& external_force_N = Vec2::Zero()) noexcept;

  [[nodiscard]] const PlantState& state() const noexcept { return state_; }
  void set_state(const PlantState& state) noexcept {
    state_ = state;
    cache_valid_ = false;
  }
  //! p_b = FK(q) (eq. 2.1), from the step's cache when it holds the current joints.
  [[nodiscard]] Vec2 base() const noexcept { return at_cache() ? cache_pb_ : robot_.forward(state_.q_rad); }
  //! ṗ_b = J(q)·q̇.
  [[nodiscard]] Vec2 base_velocity() const noexcept {
    return (at_cache() ? cache_J_ : robot_.jacobian(state_.q_rad)) * state_.qd_rad_s;
  }
  //! Static joint error under a constant tip force F (rad): Jᵀ·F/(K_v·K_p) per joint, at q.
  [[nodiscard]] Vec2 static_joint_error(const Vec2& q_rad, const Vec2& force_N) const noexcept;
  //! The drive's tuning inertia per joint (kg·m²): J_m + m_ff·(JᵀJ)_ii at the centre of C_true's rectangle.
  [[nodiscard]] const Vec2& tuning_inertia() const noexcept { return tuning_inertia_; }
  //! K(p) = (C_true(p) + L(p))⁻¹ (N/m).
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
  std::shared_ptr<const compliance::Model> lever_;
  double omega_s_;
  double controller_mass_;
  Vec2 tuning_inertia_ = Vec2::Zero();
  Vec2 kv_ = Vec2::Zero();  // velocity-loop gains (N·m·s/rad)
  double kp_ = 0.0;         // position-loop gain (1/s)
  PlantState state_;
  // The base point p_b = FK(q), J(q), and K and D at p_b, for the joints cache_q_: the end of one step
  // is the start of the next, so each step evaluates the kinematics and C_true once.
  void update_cache(const Vec2& pb, const Mat2& jacobian) noexcept;
  [[nodiscard]] bool at_cache() const noexcept { return cache_valid_ && cache_q_ == state_.q_rad; }
  bool cache_valid_ = false;
  Vec2 cache_q_ = Vec2::Zero(), cache_pb_ = Vec2::Zero();
  Mat2 cache_J_ = Mat2::Zero(), cache_K_ = Mat2::Zero(), cache_D_ = Mat2::Zero();
};

//! The symmetric square root of a symmetric positive definite 2×2 matrix (closed form:
//! √A = (A + √det A·I)/√(tr A + 2√det A)).
Mat2 sqrt_spd(const Mat2& A) noexcept;

}  // namespace stiffpath::simulation
