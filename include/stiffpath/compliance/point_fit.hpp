// Per-point first-order fits of displacement vs force, thesis eqs. 4.8–4.11, from a displacement table.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stiffpath/core/enum_names.hpp"
#include "stiffpath/core/line_fit.hpp"
#include "stiffpath/kinematics/types.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::compliance {

using core::fit_line;
using core::LineFit;
using kinematics::Mat2;
using kinematics::Vec2;

//! Which force column the fits use.
enum class ForceConvention {
  measured,  //!< F_N: the measured load relative to step 0 (default)
  nominal,   //!< F_nominal_N: the round loads the table names (the table's own column)
};

//! The four fits of eq. 4.8 at one measurement point ij, forces signed as applied (+x table: Fx > 0;
//! −y table: Fy < 0). Slopes in m/N, intercepts in m. Angular fits (rad/N) when the table has them.
struct PointFit {
  std::string id;       //!< "x1y1" …
  Vec2 position;        //!< nominal (x, y), m
  LineFit dx_fx;        //!< Δx = m·Fx + n
  LineFit dx_fy;        //!< Δx = o·Fy + p
  LineFit dy_fx;        //!< Δy = s·Fx + u
  LineFit dy_fy;        //!< Δy = v·Fy + w
  std::optional<LineFit> rx_fx, rx_fy, ry_fx, ry_fy;  //!< angular deflections about x and y

  //! [m o; s v] (m/N): eqs. 4.6–4.7 at this point.
  [[nodiscard]] Mat2 compliance() const noexcept;
  //! (n + p, u + w) (m): the thesis model's deflection at zero force.
  [[nodiscard]] Vec2 offset() const noexcept;
  //! [∂rx/∂Fx ∂rx/∂Fy; ∂ry/∂Fx ∂ry/∂Fy] (rad/N); nullopt when angles are missing.
  [[nodiscard]] std::optional<Mat2> angular_compliance() const noexcept;
};

//! One force sample of one point and direction, signed, with the measured deflection (for fits and CV).
struct PointSample {
  Vec2 force_N;                    //!< signed force vector
  std::optional<double> dx_m, dy_m;
  std::optional<double> rx_rad, ry_rad;
  int step = 0;
  int line = 0;
};

//! The samples of each point, grouped in first-appearance order.
struct PointSamples {
  std::string id;
  Vec2 position;
  std::vector<PointSample> samples;
};
std::vector<PointSamples> group_by_point(const measurement::DisplacementTable& table, ForceConvention convention);

//! Eqs. 4.8–4.11 at every point. Missing cells are skipped. Throws stiffpath::Error naming the point
//! (and the table's source) when one of the four fits has fewer than two usable load steps, or when
//! a point has no load along x or along y.
std::vector<PointFit> fit_points(const measurement::DisplacementTable& table,
                                 ForceConvention convention = ForceConvention::measured);
//! The same on already grouped samples.
PointFit fit_point(const PointSamples& point, const std::string& source);

}  // namespace stiffpath::compliance

//! Names at the edges: "measured", "nominal".
template <>
struct stiffpath::core::EnumNames<stiffpath::compliance::ForceConvention> {
  static constexpr std::string_view what = "force convention";
  static constexpr std::array<std::pair<compliance::ForceConvention, std::string_view>, 2> names{
      {{compliance::ForceConvention::measured, "measured"}, {compliance::ForceConvention::nominal, "nominal"}}};
};
