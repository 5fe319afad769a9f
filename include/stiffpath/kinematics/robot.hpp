// The robot: one value with the five-bar's geometry, mass, limits and where its compliance data lives.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/core/data_ref.hpp"
#include "stiffpath/core/enum_names.hpp"
#include "stiffpath/kinematics/five_bar.hpp"

namespace stiffpath::kinematics {

//! Limits of one actuated joint (SI).
struct JointLimit {
  std::string name;                      //!< "theta1" / "theta2"
  double min_rad = 0.0;
  double max_rad = 0.0;
  double max_velocity_rad_s = 0.0;       //!< > 0
  double max_acceleration_rad_s2 = 0.0;  //!< > 0
};

//! The CMM replica's lever lengths (thesis fig. 2.4), needed by eq. 2.3.
struct ReplicaLevers {
  double ug_m = 0.0;  //!< |UG| (the robot file's measurement.UG_mm)
  double ul_m = 0.0;  //!< |UL| > |UG| (measurement.UL_mm)
};

//! How a displacement table becomes a compliance model (docs/compliance.md). The robot file may name one;
//! the compliance module implements them.
enum class FitMethod : std::uint8_t {
  bilinear,         //!< the thesis's: per-point fits (eqs. 4.8–4.11), bilinear between the points (eq. 4.12)
  symmetric,        //!< per-point fits with C = Cᵀ ≻ 0 (reciprocity), bilinear between the points
  physical,         //!< five-bar statics C = U⁻ᵀ·D(p)·U⁻¹ with D linear in p
  physical_0,       //!< … D constant
  physical_2,       //!< … D quadratic in p
  physical_spline,  //!< physical plus a thin-plate spline of its residual at the points
};

//! Where the robot's compliance comes from. Paths are resolved against the robot file's folder.
struct ComplianceSource {
  core::DataRef table;  //!< displacement table (docs/measurement.md); empty: none
  //! The value of the table's `mechanism` column that marks this robot's rows (a table may hold
  //! several builds, as the thesis's holds OC and SC); empty: every row.
  std::string rows;
  core::DataRef model;  //!< a fitted model file; empty: fit one from the table
  //! Method used to fit the table when no model file is named; unset: the method the table's
  //! cross-validation favours.
  std::optional<FitMethod> method;
};

//! Everything stiffpath knows about one robot: a preset built into the binary (data/robots/*.json)
//! or a user's robot file with the same fields (docs/kinematics.md). SI units.
struct Robot {
  std::string name;
  std::string description;
  FiveBarGeometry geometry;
  SingularityMargin margin;
  std::array<JointLimit, 2> joints;  //!< θ1 (left actuator), θ2 (right)
  double moving_mass_kg = 0.0;       //!< everything the platform carries (thesis §4.2)
  //! Damping ratio ζ of the platform's modes on its stiffness (a ring-down identifies it): the dynamic
  //! compensation's and the input shaper's ζ, and the digital twin's, unless a caller sets its own.
  //! 0.05 when the robot file gives none (a lightly damped welded or bolted frame).
  double tip_damping_ratio = 0.05;
  //! The tip's natural frequency over the one its mass and compliance imply (1/√(m·λ(C)) · 1/2π): a calibration
  //! plate identifies it when the platform rings faster or slower than its static deflection says. The dynamic
  //! compensation's time constant T = 2ζ√(m·C) is divided by it. 1 when the robot file gives none.
  double tip_frequency_scale = 1.0;
  //! How long the laser takes to follow a switch, measured against the motion (a calibration plate identifies
  //! them; positive: late), s. The job switches the laser this much earlier. 0 when the file gives none.
  double laser_on_delay_s = 0.0;
  double laser_off_delay_s = 0.0;
  std::string cg_label = "G";        //!< name of the CG position ("G_U", "G_L": fig. 4.5)
  double cg_height_m = 0.0;          //!< height of the CG above the measured point G
  std::optional<ReplicaLevers> replica;  //!< CMM replica, when the robot is measured that way
  std::optional<Vec2> home_m;            //!< home position of the end point, m
  ComplianceSource compliance;
  core::DataRef file;  //!< where it was loaded from
  bool preset = false; //!< built into the binary

  //! The five-bar with this geometry and margin, returning θ_i within [min_i, min_i + 2π).
  [[nodiscard]] FiveBar five_bar() const;
  //! Lower-case hex SHA-256 of the geometry's canonical text (geometry_text): equal hashes, equal
  //! kinematics. Model files record it.
  [[nodiscard]] std::string geometry_hash() const;
  //! "preset oc-gu" or the file's path.
  [[nodiscard]] std::string source() const;

  //! θ for p with every check: reach (singularities, assembly mode) and the joints' position limits.
  //! Throws stiffpath::Error "point (x = … mm, y = … mm) refused: <reason>".
  [[nodiscard]] Vec2 inverse(const Vec2& p) const;
  //! The end point of joint angles q with every check: finite, each within its joint's range (an angle far
  //! beyond ±2π is named as degrees given for radians), the loop closing. Throws stiffpath::Error naming the joint.
  [[nodiscard]] Vec2 forward(const Vec2& q) const;
  //! Why p is refused (reach or a joint's range), empty when it is usable.
  [[nodiscard]] std::string refusal(const Vec2& p) const;
  //! Whether the joint angles lie within the position limits.
  [[nodiscard]] bool within_limits(const Vec2& q) const noexcept;
};

//! The largest joint zero offset a robot file may give (deg): a reading half a turn off is a wiring or
//! sign error, not an offset.
inline constexpr double kMaxJointZeroOffset_deg = 180.0;

//! The canonical text of a geometry (mm to 6 decimals, elbows, assembly; the joint zero offsets in degrees to
//! 9 decimals when either is not zero), the input of geometry_hash().
std::string geometry_text(const FiveBarGeometry& geometry);
//! SHA-256 of geometry_text().
std::string geometry_hash(const FiveBarGeometry& geometry);

//! Names of the built-in presets (oc-gu, oc-gl, sc-gu, sc-gl).
std::vector<std::string> preset_names();
//! The robot named by a preset or a JSON file. Errors name the file, line, column and field.
Robot load_robot(const std::string& preset_or_path);
//! Parses a robot file's text; `file` names it in errors and anchors its relative paths.
Robot parse_robot(std::string_view text, const core::DataRef& file);

//! Which joint quantity was violated.
enum class JointCheck { ok, position, velocity, acceleration };

//! Checks a joint state against the limits; `joint` receives the index of the first violation.
//! Inline: the compensator calls it on every sample.
inline JointCheck check_joint_limits(const std::array<JointLimit, 2>& limits, const Vec2& q, const Vec2& qd,
                                     const Vec2& qdd, int& joint) noexcept {
  for (int i = 0; i < 2; ++i) {
    const JointLimit& lim = limits[static_cast<std::size_t>(i)];
    joint = i;
    if (!(q[i] >= lim.min_rad && q[i] <= lim.max_rad)) return JointCheck::position;
    if (!(std::abs(qd[i]) <= lim.max_velocity_rad_s)) return JointCheck::velocity;
    if (!(std::abs(qdd[i]) <= lim.max_acceleration_rad_s2)) return JointCheck::acceleration;
  }
  joint = -1;
  return JointCheck::ok;
}

}  // namespace stiffpath::kinematics

//! Names at the edges (robot and model files, --method): as the enum's comments list them.
template <>
struct stiffpath::core::EnumNames<stiffpath::kinematics::FitMethod> {
  static constexpr std::string_view what = "compliance method";
  static constexpr std::array<std::pair<kinematics::FitMethod, std::string_view>, 6> names{
      {{kinematics::FitMethod::bilinear, "bilinear"},
       {kinematics::FitMethod::symmetric, "symmetric"},
       {kinematics::FitMethod::physical, "physical"},
       {kinematics::FitMethod::physical_0, "physical-0"},
       {kinematics::FitMethod::physical_2, "physical-2"},
       {kinematics::FitMethod::physical_spline, "physical-spline"}}};
};
