// Turns a raw CMM campaign into the tidy displacement table (eq. 2.3, angular deflections, averaging).
#pragma once

#include <optional>
#include <string>

#include "stiffpath/measurement/campaign.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::measurement {

//! How the force of a load step is expressed in the table's F_N column.
enum class ForceBasis {
  measured,  //!< (force − force of step 0), from the recorded kgf × 9.80665 (table 2.1; the default)
  nominal,   //!< the campaign's own nominal loads (force_nominal_N), or step × nominal_step_N when given
};

//! Options of process_campaign(). Every number comes from the robot and the campaign: take `mechanism` and
//! `geometry` from the robot (kinematics::Robot's compliance.rows and replica).
struct ProcessOptions {
  std::string mechanism;                   //!< label written in the table's mechanism column (the robot's rows)
  ReplicaGeometry geometry;                //!< |UG|, |UL| of the robot's replica
  ForceBasis force_basis = ForceBasis::measured;
  //! F_nominal_N = step × this, for a campaign without a force_nominal_N column; unset: its measured F_N.
  std::optional<double> nominal_step_N;
};

//! For each (point, direction, loaded step): G per reading by eq. 2.3, the mean G of the step minus the
//! mean G of step 0 → (dx, dy, dz); the tilt of UL (platform_pose.hpp) averaged the same way →
//! (rx, ry) relative to step 0; with two or more readings, their sample standard deviations as the
//! row's spread. F_N is per `force_basis`; F_nominal_N is the campaign's force_nominal_N, else step ×
//! nominal_step_N when given, else the measured F_N (ForceBasis::nominal refuses a campaign with neither); force_kgf is
//! the recorded absolute load in kgf. Rows come out per series in order of first appearance, steps
//! ascending. Validates the campaign first (validate_campaign) and throws stiffpath::Error on bad input.
DisplacementTable process_campaign(const Campaign& campaign, const ProcessOptions& options);

}  // namespace stiffpath::measurement
