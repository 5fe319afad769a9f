// The robot: one value with the five-bar's geometry, mass, limits and where its compliance data lives.
#pragma once

#include <array>
#include <cmath>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/core/data_ref.hpp"
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
  double ug_m = 0.069;  //!< |UG|
  double ul_m = 0.160;  //!< |UL| > |UG|
};

//! Where the robot's compliance comes from. Paths are resolved against the robot file's folder.
struct ComplianceSource {
  core::DataRef table;  //!< displacement table (docs/measurement.md); empty: none
  //! The value of the table's `mechanism` column that marks this robot's rows (a table may hold
  //! several builds, as the thesis's holds OC and SC); empty: every row.
  std::string rows;
  core::DataRef model;  //!< a fitted model file; empty: fit one from the table
  //! Method used to fit the table when no model file is named ("bilinear", "physical", …); empty:
  //! the method the table's cross-validation favours.
  std::string method;
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
//! The geometry's fields as in robot files (left_actuator_mm … elbows, assembly, and joint_zero_offsets_deg
//! when either offset is not zero).
nlohmann::json geometry_to_json(const FiveBarGeometry& geometry);

//! Names of the built-in presets (oc-gu, oc-gl, sc-gu, sc-gl).
std::vector<std::string> preset_names();
//! The robot named by a preset or a JSON file. Errors name the file, line, column and field.
Robot load_robot(const std::string& preset_or_path);
//! Parses a robot file's text; `file` names it in errors and anchors its relative paths.
Robot parse_robot(std::string_view text, const core::DataRef& file);
//! The robot as JSON, in the file format (units in the key names; paths as resolved).
nlohmann::json to_json(const Robot& robot);

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
