// Parsing of accelerations given with units on the command line.
#include "stiffpath/core/units.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include "stiffpath/core/error.hpp"

namespace stiffpath::units {

namespace {
std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}
}  // namespace

double parse_acceleration_m_s2(std::string_view text) {
  const std::string_view body = trim(text);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), value);
  const std::string_view unit = trim(std::string_view(end, body.data() + body.size() - end));
  if (ec != std::errc() || !std::isfinite(value) || value <= 0.0) {
    throw Error("acceleration '" + std::string(text) + "' is not a positive number (use e.g. 5g or 49 m/s2)");
  }
  if (unit == "g" || unit == "G") return g_to_m_s2(value);
  if (unit.empty() || unit == "m/s2" || unit == "m/s^2") return value;
  throw Error("acceleration '" + std::string(text) + "' has unknown unit '" + std::string(unit) +
              "' (use g or m/s2)");
}

}  // namespace stiffpath::units
