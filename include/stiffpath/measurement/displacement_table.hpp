// The tidy displacement table: one row per (mechanism, force direction, point, load step), as shipped
// in data/thesis/displacements.csv and as produced by CMM campaign processing.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stiffpath/core/data_ref.hpp"

namespace stiffpath::measurement {

//! Direction of the applied load (the thesis used +x and −y).
enum class ForceDirection { plus_x, minus_x, plus_y, minus_y };

//! "+x", "-x", "+y", "-y".
const char* to_string(ForceDirection direction) noexcept;
//! Unit vector components of a direction.
double direction_x(ForceDirection direction) noexcept;
double direction_y(ForceDirection direction) noexcept;

//! Spread of repeated CMM readings at one load step (sample standard deviations of the readings of G
//! and of the tilt angles about their mean; present only when the step was read two or more times).
struct ReadingSpread {
  int readings = 0;                      //!< number of readings averaged (≥ 2)
  double dx_m = 0.0, dy_m = 0.0, dz_m = 0.0;
  double rx_rad = 0.0, ry_rad = 0.0;
};

//! One measurement. Displacements are of the CG point G relative to load step 0 (eq. 2.3). A missing
//! cell (garbled in the seed, or not measured) is nullopt. All SI.
struct DisplacementRow {
  std::string mechanism;                 //!< which build the row belongs to ("OC", "SC"); empty when the table has one
  ForceDirection direction = ForceDirection::plus_x;
  std::string point;                     //!< "x1y1" … "x3y5" (or a user's id)
  double x_m = 0.0, y_m = 0.0;           //!< nominal platform position
  int step = 0;                          //!< load step, 1…n (numbered per series when the table has none)
  double force_kgf = 0.0;                //!< the absolute hanging mass as recorded (table 2.1's column); F_N/g0 if not given
  double force_N = 0.0;                  //!< magnitude relative to step 0: (kgf − kgf₀)·9.80665
  double nominal_force_N = 0.0;          //!< the round load the table names for the step; F_N if not given
  std::optional<double> dx_m, dy_m, dz_m;
  std::optional<double> rx_rad, ry_rad;  //!< angular deflections about x and y
  std::optional<ReadingSpread> spread;   //!< from campaign processing with repeated readings
  int line = 0;                          //!< source line, for errors
};

//! A whole table with its source.
struct DisplacementTable {
  std::string source;   //!< how errors name it: a path, or "builtin:thesis/displacements.csv"
  std::vector<DisplacementRow> rows;
  std::string sha256;   //!< of the file's bytes (empty for a table made in memory)

  //! Rows of one mechanism ("OC"/"SC"); an empty name selects every row of a table of one mechanism,
  //! and is refused (stiffpath::Error naming the mechanisms) for a table of several.
  [[nodiscard]] DisplacementTable filter(const std::string& mechanism) const;
  //! Distinct mechanisms present, in order of first appearance.
  [[nodiscard]] std::vector<std::string> mechanisms() const;
};

//! CSV columns as written, in order: mechanism,direction,point,x_mm,y_mm,step,force_kgf,F_N,F_nominal_N,
//! dx_mm,dy_mm,dz_mm,rx_deg,ry_deg. Empty cells are missing values. Tables with repeated readings carry
//! kSpreadColumns after these (readings,dx_sd_mm,…); readers that do not know them ignore them.
//! Reading needs only kRequiredDisplacementColumns, in any order (docs/measurement.md).
inline constexpr const char* kDisplacementColumns =
    "mechanism,direction,point,x_mm,y_mm,step,force_kgf,F_N,F_nominal_N,dx_mm,dy_mm,dz_mm,rx_deg,ry_deg";

//! The columns a table must have; the others of kDisplacementColumns are optional.
inline constexpr const char* kRequiredDisplacementColumns = "point,x_mm,y_mm,direction,F_N,dx_mm,dy_mm";

//! Optional trailing columns holding ReadingSpread (empty when a row has a single reading).
inline constexpr const char* kSpreadColumns = "readings,dx_sd_mm,dy_sd_mm,dz_sd_mm,rx_sd_deg,ry_sd_deg";

//! The thesis's data set, built into the binary (data/thesis/displacements.csv, tables 2.2–3.9).
core::DataRef thesis_dataset();

//! Loads a table. Validates every row (known direction, step ≥ 1, positive force, finite numbers, no
//! duplicated key) and throws stiffpath::Error naming file, line and column; a missing required
//! column is named with the header's line. Optional columns take the defaults documented above.
DisplacementTable load_displacement_table(const core::DataRef& file);
//! The same for CSV text already in memory; errors name `label` with the text's line and column.
DisplacementTable parse_displacement_table(const std::string& text, const std::string& label);
//! The same for a path on disk ("builtin:<path>" for a built-in file).
DisplacementTable load_displacement_table(const std::string& path);

//! Writes a table in the same CSV format (atomically); adds kSpreadColumns when any row has a spread.
void save_displacement_table(const DisplacementTable& table, const std::string& path);

}  // namespace stiffpath::measurement
