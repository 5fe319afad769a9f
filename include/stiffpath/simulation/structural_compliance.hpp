// C_true of a different family: an elastic network of the five-bar's links and parallelograms, fitted to the robot's table.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <memory>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::simulation {

//! The elastic elements of one arm (SI compliances, all ≥ 0). The arm is the thesis's parallelogram arm
//! (ch. 2.2, 3.1: the platform and the elbow bodies only translate): the actuator's torsion (motor, reducer, the
//! drive holding position) and the proximal link as an Euler–Bernoulli cantilever (bending 1/EI, stretch 1/EA,
//! the latter lumping its bearings) carry the elbow point B; an elbow body pinned at B keeps its orientation
//! through the thin bar of the proximal parallelogram (axial compliance, base pivot and body pivot both offset
//! by `proximal_bar_offset_m` from A and B); the distal link is a pin-ended bar B → C, and the thin bar of the
//! distal parallelogram (offset `distal_bar_offset_m` from B and C) joins the elbow body to the platform.
struct ArmCompliance {
  double actuator_rad_per_Nm = 0.0;
  double proximal_bending_per_Nm2 = 0.0;  //!< 1/EI of the proximal link
  double proximal_axial_per_N = 0.0;      //!< 1/EA of the proximal link and its bearings
  double distal_axial_per_N = 0.0;        //!< 1/EA of the distal link and its pins
  double proximal_bar_m_per_N = 1e4;      //!< the proximal parallelogram's thin bar (default: carries nothing)
  double distal_bar_m_per_N = 1e4;        //!< the distal parallelogram's thin bar (default: carries nothing)
  compliance::Vec2 proximal_bar_offset_m = compliance::Vec2::Zero();  //!< in the base frame (the bodies translate)
  compliance::Vec2 distal_bar_offset_m = compliance::Vec2::Zero();
  static constexpr int count = 6;  //!< the compliances, indexable by operator[]
  [[nodiscard]] double& operator[](int k) noexcept;
  [[nodiscard]] double operator[](int k) const noexcept;
};

namespace detail {
//! One arm's elements as stiffnesses (SI), constant over the workspace (the links' lengths do not change):
//! the elbow B held along the proximal link (its stretch) and across it (actuator torsion and bending in
//! series), the bars' and the distal link's axial stiffnesses, and the bars' offsets.
struct ArmSprings {
  double along_e = 0.0, across_e = 0.0;
  double proximal_bar = 0.0, distal_link = 0.0, distal_bar = 0.0;
  compliance::Vec2 proximal_offset = compliance::Vec2::Zero(), distal_offset = compliance::Vec2::Zero();
};
}  // namespace detail

//! The frame that carries both actuators (SI compliances ≥ 0), loaded by the force at C and its moment
//! about the actuators' midpoint A_0.
struct BaseCompliance {
  double x_m_per_N = 0.0;
  double y_m_per_N = 0.0;
  double rotation_rad_per_Nm = 0.0;
};

//! Structural compliance of a five-bar with parallelogram arms: a network of springs and bars assembled as
//! stiffnesses on the platform (x, y, ψ at C) and each arm's elbow body (x, y at B, ψ_E), the elbow bodies
//! condensed out, the base frame in series; the measured point G (force applied there, displacement read
//! there) sits `measured_offset_m` from C in the platform's (constant) orientation:
//! C(p) = [G_rᵀ (Σ_i K_i)⁻¹ G_r]_xy + C_base(p). Every element is a positive semi-definite stiffness, so C is
//! symmetric positive definite where the arms are not singular. The parallelograms are fixed in the base frame,
//! not in the arms' frames: the field is not invariant under rotation about the actuators, which the
//! thesis's tables require (docs/simulation.md). Not a grid, not a polynomial, not U⁻ᵀDU⁻¹: no model the
//! compensation fits has this family. Compliances below 1e-15 (m/N, rad/N·m, 1/N·m²) count as rigid at that value.
class StructuralModel final : public compliance::Model {
 public:
  //! `region`: the measured rectangle (bounds()); outside it the structure is evaluated as it is.
  StructuralModel(const kinematics::Robot& robot, std::array<ArmCompliance, 2> arms, compliance::GridBounds region,
                  BaseCompliance base = {}, compliance::Vec2 measured_offset_m = compliance::Vec2::Zero());

  [[nodiscard]] std::string description() const override { return "structural network"; }
  [[nodiscard]] compliance::Mat2 compliance(const compliance::Vec2& p) const noexcept override;
  [[nodiscard]] compliance::GridBounds bounds() const noexcept override { return region_; }
  //! Its parameters and fit statistics as JSON, as model files hold them (compliance::model_parameters).
  [[nodiscard]] nlohmann::json parameters() const;
  [[nodiscard]] const std::array<ArmCompliance, 2>& arms() const noexcept { return arms_; }
  [[nodiscard]] const BaseCompliance& base() const noexcept { return base_; }
  [[nodiscard]] const compliance::Vec2& measured_offset() const noexcept { return offset_; }

 private:
  kinematics::FiveBar five_bar_;
  std::array<ArmCompliance, 2> arms_;
  std::array<detail::ArmSprings, 2> springs_;  //!< arms_ as stiffnesses, once
  BaseCompliance base_;
  compliance::GridBounds region_;
  compliance::Vec2 offset_;
};

//! How well a structural fit reproduces its table: the largest and RMS |measured − C·F − n_s| over every
//! translation cell that is not garbled (m; n_s the offset of the cell's load series), and how many cells.
struct StructuralFitReport {
  double max_error_m = 0.0;
  double rms_error_m = 0.0;
  int cells = 0;
  int within_23um = 0;  //!< cells within the CMM's ±23 µm
};

//! The largest offset (bars, measured point) the fit allows, m: the size of the platform and elbow bodies.
inline constexpr double kStructuralMaxOffset_m = 0.06;

//! Fits the 12 arm compliances, 8 bar offsets, 3 base compliances and the measured point's offset to the
//! translations dx, dy of `table` (the robot's rows; force along the load direction, F_N as measured), each
//! load series with its own offset (eq. 4.8's intercept), by Levenberg–Marquardt (compliances on their
//! logarithms, between physical floors — no element stiffer than a steel part of the robot's size — and 100;
//! offsets within ±kStructuralMaxOffset_m) from a fixed set of starts: deterministic. A soft penalty keeps each
//! parallelogram at least 17.5° from flat over the measured rectangle (a flat parallelogram is singular), so the
//! field stays smooth between the table's points. Throws stiffpath::Error when the table has too few translations.
std::shared_ptr<StructuralModel> fit_structural_model(const kinematics::Robot& robot,
                                                      const measurement::DisplacementTable& table,
                                                      StructuralFitReport* report = nullptr);

//! The report of `model` against `table` (same measure as the fit).
StructuralFitReport structural_fit_report(const compliance::Model& model, const measurement::DisplacementTable& table);

}  // namespace stiffpath::simulation
