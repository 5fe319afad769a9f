// A CLI11 check for numeric options: finite and within documented bounds (NaN, inf and absurd magnitudes refused).
#include "bounded.hpp"

#include <cstdlib>
#include <fmt/format.h>
#include <string>

namespace stiffpath::cli {

CLI::Validator within(double low, double high, const char* unit) {
  const std::string description = fmt::format("[{:g}, {:g}]{}{}", low, high, *unit ? " " : "", unit);
  return CLI::Validator(
      [low, high, description](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return "must be a number, got '" + text + "'";
        if (!(value >= low && value <= high)) return "must be within " + description + ", got " + text;
        return {};
      },
      description);
}

CLI::Validator output_name() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? "an empty name names no file: give a path (or - for standard output where allowed)" : "";
      },
      "", "OUTPUT");
}

}  // namespace stiffpath::cli
