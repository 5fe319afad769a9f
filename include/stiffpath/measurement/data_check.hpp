// Plausibility checks of a displacement table: linearity, symmetry about y = 0, Maxwell–Betti reciprocity,
// OC vs SC; each result is flagged when it breaks its expectation by more than the measurement accuracy.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/measurement/displacement_table.hpp"
#include "stiffpath/core/line_fit.hpp"

namespace stiffpath::measurement {

using core::fit_line;
using core::LineFit;
using core::slope_through_origin;

//! The five measured quantities of a row.
enum class Quantity { dx, dy, dz, rx, ry };
inline constexpr std::array<Quantity, 5> kQuantities = {Quantity::dx, Quantity::dy, Quantity::dz, Quantity::rx,
                                                        Quantity::ry};
//! "dx" … "ry".
const char* to_string(Quantity q) noexcept;
//! The row's value of a quantity (m or rad), or nullopt when missing.
std::optional<double> value_of(const DisplacementRow& row, Quantity q) noexcept;
inline bool is_angle(Quantity q) noexcept { return q == Quantity::rx || q == Quantity::ry; }

//! Options of check_displacements().
struct DataCheckOptions {
  double accuracy_m = 23e-6;  //!< CMM accuracy of one displacement cell (Faro Prime Arm ±23 µm, §2.3)
  //! |UL| of the robot's replica: one angle cell is good to 2·accuracy/|UL| rad (U and L both off); unset for a
  //! robot measured without a replica, whose angle cells (rx, ry) are then not checked.
  std::optional<double> ul_m;
  bool nominal_forces = false;  //!< regress on the table's F_nominal_N (its round loads) instead of F_N
  //! Whether the robot is its own mirror image about y = 0 (the thesis's is); otherwise the symmetry
  //! check is skipped, since an asymmetric robot's data need not be symmetric.
  bool mirror_symmetric = true;
  //! 0 without a replica.
  [[nodiscard]] double angle_accuracy_rad() const noexcept { return ul_m ? 2.0 * accuracy_m / *ul_m : 0.0; }
};

//! Linearity of one quantity against force over the load steps of one series.
struct LinearityResult {
  std::string mechanism, point;
  ForceDirection direction = ForceDirection::plus_x;
  Quantity quantity = Quantity::dx;
  LineFit fit;             //!< slope in m/N or rad/N; residuals in m or rad
  double tolerance = 0.0;  //!< accuracy of one cell (m or rad)
  bool flagged = false;    //!< max |residual| > tolerance (needs n ≥ 3)
};

//! One symmetry comparison: the cell at (x, y) mirrored onto (x, −y), step by step (§2.5). Mirroring
//! y → −y maps (dx, dy, dz, rx, ry) to (dx, −dy, dz, −rx, ry) and a force along ±y to ∓y; when the
//! mirrored force direction was not measured, linearity gives the partner's cell negated.
struct SymmetryResult {
  std::string mechanism, point, partner;
  ForceDirection direction = ForceDirection::plus_x;
  int step = 0;
  Quantity quantity = Quantity::dx;
  double value = 0.0;       //!< the partner's measured cell
  double expected = 0.0;    //!< the point's cell mirrored
  double tolerance = 0.0;   //!< 2 × one cell's accuracy
  bool flagged = false;     //!< |value − expected| > tolerance
};

//! Maxwell–Betti at one point: ∂dx/∂Fy = ∂dy/∂Fx (slopes through the origin, signed forces).
struct ReciprocityResult {
  std::string mechanism, point;
  double c_xy_m_per_N = 0.0;    //!< x-displacement per y-force
  double c_yx_m_per_N = 0.0;    //!< y-displacement per x-force
  double max_force_N = 0.0;     //!< largest force of the two series
  double difference_m = 0.0;    //!< |c_xy − c_yx| × max force
  double tolerance = 0.0;       //!< 2 × accuracy
  bool flagged = false;
};

//! Total displacement √(dx² + dy² + dz²) of OC and SC at the same point, direction and step.
struct MechanismComparison {
  std::string point;
  ForceDirection direction = ForceDirection::plus_x;
  int step = 0;
  double force_N = 0.0;
  double oc_total_m = 0.0, sc_total_m = 0.0;
  double tolerance = 0.0;  //!< 2 × accuracy
  bool flagged = false;    //!< the over-constrained build moved more than the simple one, beyond tolerance
};

struct DataCheckReport {
  std::string source;
  DataCheckOptions options;
  std::vector<LinearityResult> linearity;
  std::vector<SymmetryResult> symmetry;
  std::vector<ReciprocityResult> reciprocity;
  std::vector<MechanismComparison> comparison;
  std::vector<std::string> skipped;  //!< checks that could not run on these data, and why (a missing partner, cells …)
  std::vector<std::string> not_applicable;  //!< checks that do not apply to this robot or table, and why
  [[nodiscard]] int flagged_count() const noexcept;
};

//! Runs every check on a table. Never throws on missing cells (they are skipped); throws
//! stiffpath::Error for invalid options.
DataCheckReport check_displacements(const DisplacementTable& table, const DataCheckOptions& options = {});

//! The symmetry part alone (used by check_displacements).
std::vector<SymmetryResult> check_symmetry(const DisplacementTable& table, const DataCheckOptions& options,
                                           std::vector<std::string>& skipped);

}  // namespace stiffpath::measurement
