// A robot as configured by a preset or user JSON file: geometry, mass, CG, limits, compliance data set.
#pragma once

#include <array>
#include <cmath>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

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

//! Everything stiffpath needs to know about one build of the robot. Loaded from
//! data/mechanisms/*.json (built into the binary) or a user's file with the same fields.
struct MechanismSpec {
  std::string name;                    //!< e.g. "oc-gu"
  std::string description;
  std::string build;                   //!< "OC" (over-constrained 6R) or "SC" (simply-constrained 6R)
  double link_length_m = 0.150;        //!< l, all four links (thesis §2.2)
  double moving_mass_kg = 3.6;         //!< platform + laser head (thesis §4.2)
  std::string cg_label;                //!< "G_U" or "G_L" (fig. 4.5)
  double cg_height_m = 0.0;            //!< height of the CG above the measured point G (fig. 4.5)
  double ug_m = 0.069;                 //!< |UG| of the measurement replica (fig. 2.4)
  double ul_m = 0.160;                 //!< |UL| (fig. 2.4)
  std::array<JointLimit, 2> joints;    //!< θ1, θ2
  SingularityMargin margin;
  std::string compliance_dataset;      //!< data set under data/ (e.g. "thesis/oc_displacements.csv")
  std::string source;                  //!< where it was loaded from ("preset oc-gu" or a path)

  //! The five-bar with this spec's link length and margin.
  [[nodiscard]] FiveBar five_bar() const { return FiveBar(link_length_m, margin); }
};

//! Names of the built-in presets (oc-gu, oc-gl, sc-gu, sc-gl).
std::vector<std::string> preset_names();
//! A preset name or a path to a JSON file. Errors name the file and the bad field.
MechanismSpec load_mechanism(const std::string& preset_or_path);
//! Validates a parsed document field by field; `label` names it in errors.
MechanismSpec parse_mechanism(const nlohmann::json& document, const std::string& label);
//! The spec as JSON, in the file format (units in the key names).
nlohmann::json to_json(const MechanismSpec& spec);

//! Which joint quantity was violated.
enum class JointCheck { ok, position, velocity, acceleration };

//! Checks a joint state against the limits; `joint` receives the index of the first violation.
//! Inline: the compensator calls it on every sample.
inline JointCheck check_joint_limits(const MechanismSpec& spec, const Vec2& q, const Vec2& qd, const Vec2& qdd,
                                     int& joint) noexcept {
  for (int i = 0; i < 2; ++i) {
    const JointLimit& lim = spec.joints[static_cast<std::size_t>(i)];
    joint = i;
    if (!(q[i] >= lim.min_rad && q[i] <= lim.max_rad)) return JointCheck::position;
    if (!(std::abs(qd[i]) <= lim.max_velocity_rad_s)) return JointCheck::velocity;
    if (!(std::abs(qdd[i]) <= lim.max_acceleration_rad_s2)) return JointCheck::acceleration;
  }
  joint = -1;
  return JointCheck::ok;
}

}  // namespace stiffpath::kinematics
