// Planning the poses of a geometry calibration (D-optimal, spread, within reach), and rehearsing it with virtual readings.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/calibration/geometry_fit.hpp"
#include "stiffpath/calibration/geometry_model.hpp"
#include "stiffpath/calibration/geometry_readings.hpp"
#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::calibration {

//! Settings of plan_geometry_poses(), with documented defaults.
struct GeometryPlanSettings {
  int poses = 30;  //!< how many poses (4 … kMaxPlannedPoses)
  //! Where the poses may lie (robot frame, m); empty: anywhere the robot reaches within its singularity margin
  //! and joint limits (the instrument must reach there too).
  std::optional<compliance::GridBounds> region;
  //! Candidate end points: a square lattice of about this many points over the reachable region.
  int candidates = 4000;
  //! Only poses where J's condition number is at most this (and within the robot's own margin): away from the
  //! singularities, where the tool point moves most per error of a part and the robot is least stiff.
  double max_condition_number = 4.0;
  //! No two poses closer than this fraction of √(reachable area / poses): well spread, not stacked on the
  //! few most informative spots.
  double min_separation_fraction = 0.8;
  //! Passes of pose exchange (Fedorov) after the greedy choice; each swaps a pose for a better candidate.
  int exchange_passes = 3;
  GeometryFitSettings fit;  //!< the parameters' scales and the instrument's noise, as the fit will use them
};

//! The most poses a plan may have.
inline constexpr int kMaxPlannedPoses = 1000;

struct PlannedPose {
  kinematics::Vec2 q_rad = kinematics::Vec2::Zero();  //!< joint readings to command
  kinematics::Vec2 p_m = kinematics::Vec2::Zero();    //!< the end point the robot file's geometry predicts
  double condition_number = 0.0;                     //!< of J there
};

struct GeometryPlan {
  std::vector<PlannedPose> poses;  //!< in a measuring order (nearest neighbour from the first)
  std::vector<kinematics::Vec2> reachable;  //!< the candidate lattice (for the picture)
  double lattice_step_m = 0.0;
  double min_separation_m = 0.0;
  double max_condition_number = 0.0;  //!< the candidates' limit (the settings' or the robot's own, the smaller)
  std::vector<std::string> held;  //!< parameters the readings cannot separate (held at the robot file's values)
  //! Each parameter's σ predicted for planar readings with the settings' noise (SI; 0 when held or not applicable).
  std::vector<double> predicted_sigma;
  double log_det = 0.0;  //!< log det of the scaled information matrix of the fitted parameters (the plan's criterion)
};

//! Chooses `settings.poses` poses that determine the geometry best: candidates on a lattice over the robot's
//! reachable region (Robot::refusal: reach, singularity margin, joint limits; condition number ≤
//! max_condition_number), the parameters the readings
//! cannot separate held as fit_geometry holds them, then greedy D-optimal selection (each step adds the
//! candidate that most increases det(Σ JᵢᵀJᵢ) of the scaled Jacobian, kept min_separation apart) and pose
//! exchange. Deterministic. Throws stiffpath::Error when the region holds fewer candidates than poses.
GeometryPlan plan_geometry_poses(const kinematics::Robot& robot, const GeometryPlanSettings& settings = {});
//! The same criterion for given poses (to compare a plan with another layout): log det of the scaled
//! information of the parameters the plan fits.
double geometry_log_det(const kinematics::Robot& robot, const std::vector<kinematics::Vec2>& q_rad,
                        const GeometryPlanSettings& settings = {});

//! Writes a plan as `pose,theta1_deg,theta2_deg,x_mm,y_mm,condition_number` (x, y: the robot file's prediction).
void save_geometry_plan(const GeometryPlan& plan, const std::string& path);
//! Reads the poses (theta1_deg, theta2_deg) of a plan file or of any file with those columns.
std::vector<kinematics::Vec2> load_pose_angles(const std::string& path);

//! Options of simulate_geometry_readings().
struct GeometryRehearsal {
  InstrumentFrame frame;           //!< where the instrument stands
  double noise_sigma_m = 11.5e-6;  //!< σ of every coordinate (the arm's ±23 µm as 2σ)
  int readings_per_pose = 1;
  bool spatial = false;            //!< give z as well
  std::uint64_t seed = 1;
};

//! What an instrument would read at the poses of a robot whose true geometry is `truth`.
GeometryReadings simulate_geometry_readings(const kinematics::FiveBarGeometry& truth,
                                            const std::vector<kinematics::Vec2>& q_rad, const GeometryRehearsal& options);

}  // namespace stiffpath::calibration
