// A CMM compliance campaign as recorded: per point, force direction, load step and reading, the two
// measured points U and L of the laser-head replica (thesis §2.4). Raw format documented in docs/measurement.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stiffpath/measurement/displacement_table.hpp"
#include "stiffpath/measurement/platform_pose.hpp"

namespace stiffpath::measurement {

//! One CMM reading of U and L (SI).
struct CampaignReading {
  std::string point;       //!< point id, e.g. "x1y1"
  double x_m = 0.0;        //!< nominal platform position
  double y_m = 0.0;
  ForceDirection direction = ForceDirection::plus_x;
  int step = 0;            //!< load step; 0 is the reference (the hanging system alone)
  int reading = 1;         //!< repeat index within the step (1 when not repeated)
  double force_N = 0.0;    //!< absolute hanging load of this step, as recorded (kgf × 9.80665 or N)
  //! The round load the campaign names for this step relative to step 0 (its force_nominal_N column, N);
  //! unset when the file has no such column.
  std::optional<double> nominal_force_N;
  Vec3 U = Vec3::Zero();   //!< upper measured point (m)
  Vec3 L = Vec3::Zero();   //!< lower measured point (m)
  int line = 0;            //!< source line, for errors
};

//! Unit of the force column of a campaign file.
enum class ForceUnit { kgf, N };

//! A whole campaign with its source.
struct Campaign {
  std::string source;
  ForceUnit force_unit = ForceUnit::kgf;  //!< how the file gave the force (force_kgf or force_N)
  bool has_nominal_forces = false;        //!< the file has a force_nominal_N column
  std::vector<CampaignReading> readings;
};

//! Columns of the raw format: point,x_mm,y_mm,direction,step,[reading,]force_kgf|force_N,[force_nominal_N,]
//! Ux_mm,Uy_mm,Uz_mm,Lx_mm,Ly_mm,Lz_mm. Extra columns (a comment, a date) are ignored. force_nominal_N, when
//! given, is the round load each step is meant to add to step 0 (0 on step 0; one value per step).
inline constexpr const char* kCampaignColumns =
    "point,x_mm,y_mm,direction,step,reading,force_kgf,Ux_mm,Uy_mm,Uz_mm,Lx_mm,Ly_mm,Lz_mm";

//! Reads and validates a campaign file. Throws stiffpath::Error naming file, line and column for: a
//! missing column, a column in another unit (Ux_in, force_lbf, x_m …), an empty or non-finite cell, an
//! unknown direction, a negative step or reading, a duplicated (point, direction, step, reading), a
//! point whose nominal coordinates change, a force that differs between readings of one step, and a
//! (point, direction) series without step 0 or with fewer than two loaded steps.
Campaign load_campaign(const std::string& path);

//! Writes a campaign in the raw format (force_kgf column; U, L in mm with 6 decimals), atomically.
void save_campaign(const Campaign& campaign, const std::string& path);

}  // namespace stiffpath::measurement
