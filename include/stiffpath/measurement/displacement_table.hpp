// The tidy displacement table: one row per (mechanism, force direction, point, load step), as shipped
// in data/thesis/displacements.csv and as produced by CMM campaign processing.
#pragma once

#include <optional>
#include <string>
#include <vector>

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
  std::string mechanism;                 //!< "OC" or "SC"
  ForceDirection direction = ForceDirection::plus_x;
  std::string point;                     //!< "x1y1" … "x3y5" (or a user's id)
  double x_m = 0.0, y_m = 0.0;           //!< nominal platform position
  int step = 0;                          //!< load step, 1…n
  double force_kgf = 0.0;                //!< hanging mass as in table 2.1 (includes step 0's 0.11 kgf)
  double force_N = 0.0;                  //!< magnitude relative to step 0: (kgf − kgf₀)·9.80665
  double nominal_force_N = 0.0;          //!< the thesis's rounded value (50 … 250 N)
  std::optional<double> dx_m, dy_m, dz_m;
  std::optional<double> rx_rad, ry_rad;  //!< angular deflections about x and y
  std::optional<ReadingSpread> spread;   //!< from campaign processing with repeated readings
  int line = 0;                          //!< source line, for errors
};

//! A whole table with its source (path, or "thesis" for the built-in data set).
struct DisplacementTable {
  std::string source;
  std::vector<DisplacementRow> rows;

  //! Rows of one mechanism ("OC"/"SC"); empty if none.
  [[nodiscard]] DisplacementTable filter(const std::string& mechanism) const;
  //! Distinct mechanisms present, in order of first appearance.
  [[nodiscard]] std::vector<std::string> mechanisms() const;
};

//! CSV columns, in order: mechanism,direction,point,x_mm,y_mm,step,force_kgf,F_N,F_nominal_N,
//! dx_mm,dy_mm,dz_mm,rx_deg,ry_deg. Empty cells are missing values. Tables with repeated readings carry
//! kSpreadColumns after these (readings,dx_sd_mm,…); readers that do not know them ignore them.
inline constexpr const char* kDisplacementColumns =
    "mechanism,direction,point,x_mm,y_mm,step,force_kgf,F_N,F_nominal_N,dx_mm,dy_mm,dz_mm,rx_deg,ry_deg";

//! Optional trailing columns holding ReadingSpread (empty when a row has a single reading).
inline constexpr const char* kSpreadColumns = "readings,dx_sd_mm,dy_sd_mm,dz_sd_mm,rx_sd_deg,ry_sd_deg";

//! Loads a table from a file, or the built-in thesis data set when `path` is "thesis". Validates every
//! row (known mechanism and direction, step ≥ 1, finite numbers, no duplicated key) and throws
//! stiffpath::Error naming file, line and column.
DisplacementTable load_displacement_table(const std::string& path);

//! Writes a table in the same CSV format (atomically); adds kSpreadColumns when any row has a spread.
void save_displacement_table(const DisplacementTable& table, const std::string& path);

}  // namespace stiffpath::measurement
