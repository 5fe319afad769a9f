// C_true of a different family: a virtual-joint (structural) model of the five-bar, fitted to the robot's table.
#pragma once

#include <array>
#include <memory>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::simulation {

//! The elastic elements of one arm (SI compliances, all ≥ 0): the actuator's torsion (motor, reducer and
//! the drive holding position), the proximal and distal links as Euler–Bernoulli cantilevers (bending 1/EI,
//! stretch 1/EA), a torsional spring in the elbow joint (bearing preload, the over-constrained build's
//! redundant joints: a moment-carrying elbow, so the distal link is not a two-force member) and radial
//! play of the end pin.
struct ArmCompliance {
  double actuator_rad_per_Nm = 0.0;
  double proximal_bending_per_Nm2 = 0.0;  //!< 1/EI of the proximal link
  double proximal_axial_per_N = 0.0;      //!< 1/EA of the proximal link
  double distal_bending_per_Nm2 = 0.0;
  double distal_axial_per_N = 0.0;
  double elbow_rad_per_Nm = 0.0;
  double pin_m_per_N = 0.0;
  static constexpr int count = 7;
  [[nodiscard]] double& operator[](int k) noexcept;
  [[nodiscard]] double operator[](int k) const noexcept;
};

//! The frame that carries both actuators (SI compliances ≥ 0), loaded by the force at C and its moment
//! about the actuators' midpoint A_0.
struct BaseCompliance {
  double x_m_per_N = 0.0;
  double y_m_per_N = 0.0;
  double rotation_rad_per_Nm = 0.0;
};

//! Structural compliance of a five-bar (virtual-joint method, Pashkevich et al. 2009): each arm is a
//! serial chain A_i → B_i → C of the elements of ArmCompliance; its compliance at C under a wrench
//! (F, M) is Σ_e G_eᵀ R_e C_e R_eᵀ G_e (G_e moves the wrench from C to the element, R_e turns the
//! element's frame). The end pin transmits no moment, so arm i resists a force at C with
//! K_i = (C_arm,i)_{xy}⁻¹ and the arms act in parallel, in series with the base frame:
//! C(p) = (K_1 + K_2)⁻¹ + (G_bᵀ C_b G_b)_{xy}. Not of the form
//! U⁻ᵀ D U⁻¹ (the elbow springs make the distal links bend), not a grid, not a polynomial: no model
//! the compensation fits has this family. Symmetric positive definite wherever the arms are.
class StructuralModel final : public compliance::Model {
 public:
  //! `region`: the measured rectangle (bounds()); outside it the structure is evaluated as it is.
  StructuralModel(const kinematics::Robot& robot, std::array<ArmCompliance, 2> arms, compliance::GridBounds region,
                  BaseCompliance base = {});

  [[nodiscard]] std::string method() const override { return "structural"; }
  [[nodiscard]] compliance::Mat2 compliance(const compliance::Vec2& p) const noexcept override;
  [[nodiscard]] compliance::GridBounds bounds() const noexcept override { return region_; }
  [[nodiscard]] nlohmann::json parameters() const override;
  [[nodiscard]] const std::array<ArmCompliance, 2>& arms() const noexcept { return arms_; }

 private:
  kinematics::FiveBar five_bar_;
  std::array<ArmCompliance, 2> arms_;
  BaseCompliance base_;
  compliance::GridBounds region_;
};

//! How well a structural fit reproduces its table: the largest and RMS |measured − C·F| over every
//! translation cell that is not garbled (m), and how many cells there were.
struct StructuralFitReport {
  double max_error_m = 0.0;
  double rms_error_m = 0.0;
  int cells = 0;
  int within_23um = 0;  //!< cells within the CMM's ±23 µm
};

//! Fits the 14 arm and 3 base compliances to the translations dx, dy of `table` (the robot's rows; force along the
//! load direction, F_N as measured) by Levenberg–Marquardt on their logarithms (so they stay ≥ 0),
//! from several starts. Throws stiffpath::Error when the table has no translations.
std::shared_ptr<StructuralModel> fit_structural_model(const kinematics::Robot& robot,
                                                      const measurement::DisplacementTable& table,
                                                      StructuralFitReport* report = nullptr);

//! The report of `model` against `table` (same measure as the fit).
StructuralFitReport structural_fit_report(const compliance::Model& model, const measurement::DisplacementTable& table);

}  // namespace stiffpath::simulation
