// Unit conversions at the edges of the library (mm, degrees, kgf, mm/min, g) to and from SI.
#pragma once

#include <numbers>
#include <string_view>

namespace stiffpath::units {

inline constexpr double standard_gravity_m_s2 = 9.80665;  //!< 1 g and 1 kgf/kg (CGPM 1901)

constexpr double mm_to_m(double mm) noexcept { return mm * 1e-3; }
constexpr double m_to_mm(double m) noexcept { return m * 1e3; }
constexpr double m_to_um(double m) noexcept { return m * 1e6; }
constexpr double um_to_m(double um) noexcept { return um * 1e-6; }
constexpr double deg_to_rad(double deg) noexcept { return deg * std::numbers::pi / 180.0; }
constexpr double rad_to_deg(double rad) noexcept { return rad * 180.0 / std::numbers::pi; }
constexpr double kgf_to_N(double kgf) noexcept { return kgf * standard_gravity_m_s2; }
constexpr double mm_per_min_to_m_s(double v) noexcept { return v * 1e-3 / 60.0; }
constexpr double g_to_m_s2(double g) noexcept { return g * standard_gravity_m_s2; }

//! Parses an acceleration given on a command line: "5g", "2.5 g" or a plain number in m/s² ("49.03",
//! "49.03m/s2"). Throws stiffpath::Error naming the text when it is not a positive finite number.
double parse_acceleration_m_s2(std::string_view text);

}  // namespace stiffpath::units
