// The general planar five-bar: two actuated base joints, a proximal and a distal link per side, a working mode.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "stiffpath/kinematics/mechanism.hpp"

namespace stiffpath::kinematics {

//! Geometry of a planar five-bar (SI). Arm i (0 = left, 1 = right) runs from its actuator A_i through
//! the proximal link (length l_pi, angle θ_i, actuated) to the elbow B_i and through the distal link
//! (length l_di) to the end point C, where the two distal links meet in a pin joint.
struct FiveBarGeometry {
  std::array<Vec2, 2> actuator_m{Vec2::Zero(), Vec2::Zero()};  //!< A_1 (left), A_2 (right), m
  std::array<double, 2> proximal_m{0.0, 0.0};  //!< l_p1, l_p2, m (every robot's own: no default length)
  std::array<double, 2> distal_m{0.0, 0.0};    //!< l_d1, l_d2, m
  //! Working mode s_i: +1 puts elbow B_i counter-clockwise of the line from A_i to C, −1 clockwise.
  //! θ_i = φ_i + s_i·α_i with φ_i the direction of A_iC and α_i the angle between A_iC and A_iB_i.
  std::array<int, 2> elbows{+1, -1};
  //! Assembly mode σ: the sign of u_1 × u_2 (u_i the unit vector from B_i to C), i.e. +1 when C lies to
  //! the left of the line from B_1 to B_2. It only changes through the parallel singularity.
  int assembly = +1;
  //! Joint zero offsets δ_i (rad): at a joint reading θ_i (what the drive is commanded and reports) the
  //! proximal link stands at θ_i + δ_i. Zero for the presets; a geometry calibration identifies them.
  //! Forward kinematics adds them, inverse kinematics subtracts them, joint limits apply to θ_i.
  std::array<double, 2> joint_zero_rad{0.0, 0.0};

  //! The thesis's robot (§2.2): both actuators at the origin, four links of `link_length_m`, elbows
  //! [+1, −1], assembly +1: C = l·(e^{iθ1} + e^{iθ2}) (eq. 2.1).
  static FiveBarGeometry thesis(double link_length_m) noexcept;
  //! True when this is exactly the thesis's special case (bit-for-bit equal fields, zero offsets zero), for
  //! which the closed forms of eqs. 2.1–2.2 are used.
  [[nodiscard]] bool is_thesis_case() const noexcept;
  [[nodiscard]] bool operator==(const FiveBarGeometry& other) const noexcept;
  //! Whether the mirror y → −y maps the robot onto itself (the left arm onto the right one): the
  //! actuators mirror each other, the arms have equal links and opposite elbows.
  [[nodiscard]] bool mirror_symmetric_about_x() const noexcept;
};

//! Passive angles of the distal links (absolute, rad): θ3 of the left one, θ4 of the right one.
//! For the thesis robot eq. 2.2 gives θ3 = θ2, θ4 = θ1 (parallelogram loops).
struct PassiveAngles {
  double theta3_rad = 0.0;
  double theta4_rad = 0.0;
};

//! What the real-time inverse leaves behind so that J and J̇ need no further trigonometry.
struct InverseFrame {
  Mat2 jacobian = Mat2::Zero();                    //!< J = ∂C/∂θ at the solution
  std::array<Vec2, 2> proximal{Vec2::Zero(), Vec2::Zero()};  //!< e_i = (cos θ_i, sin θ_i)
  std::array<Vec2, 2> distal{Vec2::Zero(), Vec2::Zero()};    //!< u_i = (C − B_i)/l_di
};

//! The planar five-bar. Inverse kinematics in the working mode `elbows`: per arm
//! α_i = acos((r_i² + l_pi² − l_di²)/(2 r_i l_pi)), θ_i = φ_i + s_i α_i. Forward kinematics in the
//! assembly mode `assembly`: C is the intersection of the distal links' circles about B_1 and B_2 on
//! the side σ. Velocity level from the loop closure C = A_i + l_pi e_i + l_di u_i: u_i·Ċ = l_pi θ̇_i
//! (u_i·e_i⊥), i.e. A·Ċ = B·θ̇ with A = [u_1ᵀ; u_2ᵀ], B = diag(l_pi u_i·e_i⊥), J = A⁻¹B. Serial
//! singularities: u_i ∥ e_i (|A_iC| = l_pi ± l_di); parallel: u_1 ∥ u_2 (det A = 0).
//!
//! For the thesis's geometry (FiveBarGeometry::is_thesis_case) every method uses the thesis's closed
//! forms instead (eqs. 2.1–2.2, J = l[−sin θ1, −sin θ2; cos θ1, cos θ2]), bit for bit as before.
class FiveBar final : public Mechanism {
 public:
  //! The thesis's robot with links of `link_length_m` (> 0) and the margin.
  explicit FiveBar(double link_length_m, SingularityMargin margin = {});
  //! Any five-bar; throws stiffpath::Error for non-positive or non-finite lengths, elbows or assembly
  //! other than ±1, or a margin that leaves no workspace. `angle_floor_rad`: the general inverse
  //! returns θ_i in [floor_i, floor_i + 2π) (set it to the joints' lower limits).
  FiveBar(const FiveBarGeometry& geometry, SingularityMargin margin,
          std::array<double, 2> angle_floor_rad = {-3.141592653589793, -3.141592653589793});

  [[nodiscard]] const FiveBarGeometry& geometry() const noexcept { return g_; }
  [[nodiscard]] const SingularityMargin& margin() const noexcept { return margin_; }
  //! Whether the thesis's closed forms are in use.
  [[nodiscard]] bool thesis_case() const noexcept { return thesis_; }

  //! Eq. 2.1 for the thesis; otherwise the circle intersection in the assembly mode. Where the distal
  //! links cannot close (|B_1B_2| > l_d1 + l_d2 or < |l_d1 − l_d2|) it returns the nearest almost-closed
  //! point; forward_checked() says so.
  [[nodiscard]] Vec2 forward(const Vec2& q) const noexcept override;
  //! Forward kinematics that throws stiffpath::Error naming the angles when the loop cannot close.
  [[nodiscard]] Vec2 forward_checked(const Vec2& q) const;
  //! Inverse kinematics with the reach check of check_reach().
  [[nodiscard]] InverseResult solve_inverse(const Vec2& p) const noexcept override;
  //! The same, also giving J (and what J̇ needs) at the solution without further trigonometry.
  //! `frame` is left unchanged unless the status is ok. For the real-time path: noexcept, no allocation.
  [[nodiscard]] InverseResult solve_inverse(const Vec2& p, InverseFrame& frame) const noexcept;
  //! The same with J only.
  [[nodiscard]] InverseResult solve_inverse(const Vec2& p, Mat2& jacobian) const noexcept;
  //! J̇ at the frame's solution for joint rates q̇. Thesis: each column of J rotates with its joint,
  //! J̇ = R90·J·diag(q̇). General: J̇ = A⁻¹(Ḃ − ȦJ) with u̇_i = ψ̇_i u_i⊥,
  //! ψ̇_i = (Ċ − l_pi θ̇_i e_i⊥)·u_i⊥ / l_di and Ḃ_ii = l_pi (u_i·e_i)(ψ̇_i − θ̇_i).
  [[nodiscard]] Mat2 jacobian_dot(const InverseFrame& frame, const Vec2& qd) const noexcept;
  //! J at q (through forward kinematics in the general case).
  [[nodiscard]] Mat2 jacobian(const Vec2& q) const noexcept override;
  //! J̇ at (q, q̇).
  [[nodiscard]] Mat2 jacobian_dot(const Vec2& q, const Vec2& qd) const noexcept override;
  [[nodiscard]] Reach check_reach(const Vec2& p) const noexcept override;
  //! Closed form from J: κ = (s + √(s² − 4d²))/(2|d|), s = ‖J‖_F², d = det J. Thesis:
  //! sqrt((1 + |cos(θ1 − θ2)|)/(1 − |cos(θ1 − θ2)|)).
  [[nodiscard]] double condition_number(const Vec2& q) const noexcept override;

  //! The distal links' absolute angles at q (thesis: θ3 = θ2, θ4 = θ1 by eq. 2.2).
  [[nodiscard]] PassiveAngles passive_angles(const Vec2& q) const noexcept;
  //! The elbows B_1, B_2 at joint readings q (m).
  [[nodiscard]] std::array<Vec2, 2> elbows(const Vec2& q) const noexcept;
  //! The refusal of p in words, with the arm and the numbers ("left arm stretched out: |A1C| =
  //! 299.000 mm > l_p + l_d − margin = 295.000 mm"); empty when p is reachable.
  [[nodiscard]] std::string explain(const Vec2& p) const override;

 private:
  struct ArmLimits {
    double outer_m = 0.0;  // l_p + l_d − margin
    double inner_m = 0.0;  // |l_p − l_d| + margin
  };
  [[nodiscard]] InverseResult solve_thesis(const Vec2& p, InverseFrame* frame) const noexcept;
  [[nodiscard]] InverseResult solve_general(const Vec2& p, InverseFrame* frame) const noexcept;
  //! C and the distal unit vectors at q; false when the loop cannot close (C is then the nearest point).
  bool close_loop(const Vec2& q, Vec2& c, std::array<Vec2, 2>& u) const noexcept;
  //! The proximal links' absolute angles at joint readings q: q + δ.
  [[nodiscard]] Vec2 links(const Vec2& q) const noexcept { return {q.x() + g_.joint_zero_rad[0], q.y() + g_.joint_zero_rad[1]}; }

  FiveBarGeometry g_;
  SingularityMargin margin_;
  std::array<double, 2> angle_floor_;
  bool thesis_ = false;
  double l_ = 0.0;           // the thesis's link length
  double inverse_2l_ = 0.0;  // 1 / (2l), for the thesis's real-time inverse
  std::array<ArmLimits, 2> arm_{};
  double min_distal_sine_ = 0.0;  // sin(min_distal_angle)
};

}  // namespace stiffpath::kinematics
