// Turns a raw CMM campaign into the tidy displacement table (eq. 2.3, angular deflections, averaging).
#pragma once

#include <string>

#include "stiffpath/measurement/campaign.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::measurement {

//! How the force of a load step is expressed in the table's F_N column.
enum class ForceBasis {
  measured,  //!< (force − force of step 0), from the recorded kgf × 9.80665 (table 2.1; the default)
  nominal,   //!< step × nominal_step_N (50, 100, … 250 N), as the thesis's tables and fit did
};

//! Options of process_campaign(). Defaults are the thesis's setup.
struct ProcessOptions {
  std::string mechanism = "OC";            //!< label written in the table's mechanism column
  ReplicaGeometry geometry;                //!< |UG|, |UL| (take them from kinematics::Robot::replica)
  ForceBasis force_basis = ForceBasis::measured;
  double nominal_step_N = 50.0;            //!< F_nominal_N = step × this (table 2.1's "≈ in N" column)
};

//! For each (point, direction, loaded step): G per reading by eq. 2.3, the mean G of the step minus the
//! mean G of step 0 → (dx, dy, dz); the tilt of UL (platform_pose.hpp) averaged the same way →
//! (rx, ry) relative to step 0; with two or more readings, their sample standard deviations as the
//! row's spread. F_N is per `force_basis`; F_nominal_N is always step × nominal_step_N; force_kgf is
//! the recorded absolute load in kgf. Rows come out per series in order of first appearance, steps
//! ascending. Validates the campaign first (validate_campaign) and throws stiffpath::Error on bad input.
DisplacementTable process_campaign(const Campaign& campaign, const ProcessOptions& options);

}  // namespace stiffpath::measurement
