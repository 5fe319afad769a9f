// A virtual CMM campaign: known displacements and rotations → U and L readings with the arm's noise, so that
// campaign processing can be tested by round trip (and users can rehearse a campaign).
#pragma once

#include <cstdint>

#include "stiffpath/measurement/campaign.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::measurement {

//! Options of simulate_campaign(). Defaults: the thesis's replica and the Faro Prime Arm.
struct VirtualCampaignOptions {
  ReplicaGeometry geometry;           //!< |UG|, |UL| of the replica (fig. 2.4)
  int readings_per_step = 1;          //!< repeated readings of U and L at each load step (≥ 1)
  double noise_sigma_m = 11.5e-6;     //!< σ of the Gaussian error of every coordinate of U and L: the
                                      //!< arm's ±23 µm (§2.3) taken as a 2σ bound; 0 = exact readings
  std::uint64_t seed = 1;             //!< random seed (same seed, same readings on one platform)
  double step0_kgf = 0.0;             //!< hanging load of the reference step 0 (step0_load_kgf of the truth)
  double g_height_m = 0.0;            //!< z of G at step 0 in the CMM frame
  Tilt initial_tilt;                  //!< tilt of the replica at step 0 (a real platform is never level)
};

//! The hanging load of a table's reference step 0 (kgf): what its absolute force_kgf exceeds its relative F_N
//! by (the thesis's table 2.1: the 0.11 kgf wire system), to the µkgf; 0 for a table whose forces are only in N.
double step0_load_kgf(const DisplacementTable& table);

//! Readings of a campaign whose true displacements and tilts are `truth` (one mechanism; every dx, dy,
//! dz, rx, ry cell present, else stiffpath::Error naming the row's line). Step 0 of each series has G
//! at (x, y, g_height) and the initial tilt; step k has G + (dx, dy, dz) and the tilt plus (rx, ry).
//! Forces: step 0 → step0_kgf, step k → the truth row's force_kgf. Throws on invalid options.
Campaign simulate_campaign(const DisplacementTable& truth, const VirtualCampaignOptions& options);

//! A complete, smooth stand-in for a measured table: every dx … ry cell of every row replaced by the
//! series' least-squares line through the origin against F_N (fitted to the cells present). A model of
//! the data, used as the truth of virtual campaigns built from the thesis data set (which has gaps).
//! A quantity absent from the whole table (dz, rx, ry are optional) becomes zero; one absent from a
//! single series while others have it is an error.
DisplacementTable linear_truth(const DisplacementTable& table);
//! Whether some row lacks a quantity (dx … ry) that other rows of the table have: a gap.
bool has_gaps(const DisplacementTable& table);
//! The table with every quantity it lacks entirely (dz, rx, ry are optional columns) set to zero.
DisplacementTable zero_absent_quantities(const DisplacementTable& table);

}  // namespace stiffpath::measurement
