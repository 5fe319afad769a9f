// Warnings counted by kind and the refusals of a whole program gathered into one error.
#include "stiffpath/motion/gcode_diagnostics.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

namespace stiffpath::motion {

const char* to_string(GcodeWarningKind kind) noexcept {
  switch (kind) {
    case GcodeWarningKind::z_ignored: return "z_ignored";
    case GcodeWarningKind::tool_ignored: return "tool_ignored";
    case GcodeWarningKind::program_stop: return "program_stop";
    case GcodeWarningKind::block_delete: return "block_delete";
    case GcodeWarningKind::power_clamped: return "power_clamped";
    case GcodeWarningKind::laser_without_power: return "laser_without_power";
    case GcodeWarningKind::long_dwell: return "long_dwell";
    case GcodeWarningKind::fan_as_laser: return "fan_as_laser";
    case GcodeWarningKind::output_as_laser: return "output_as_laser";
    case GcodeWarningKind::output_ignored: return "output_ignored";
    case GcodeWarningKind::tool_length_ignored: return "tool_length_ignored";
    case GcodeWarningKind::plane_arc_as_line: return "plane_arc_as_line";
    case GcodeWarningKind::m_code_ignored: return "m_code_ignored";
    case GcodeWarningKind::start_at_home: return "start_at_home";
  }
  return "unknown";
}

void GcodeWarnings::add(GcodeWarningKind kind, int line, const std::string& message) {
  const auto found = std::find_if(list_.begin(), list_.end(), [kind](const GcodeWarning& w) { return w.kind == kind; });
  if (found != list_.end()) {
    ++found->count;
    return;
  }
  list_.push_back({kind, message, 1, line});
}

std::string describe(const GcodeWarning& warning, const std::string& file) {
  if (warning.count == 1) return fmt::format("{}:{}: {}", file, warning.first_line, warning.message);
  return fmt::format("{}:{}: {} ({} lines, the first shown)", file, warning.first_line, warning.message, warning.count);
}

namespace {

std::string rest_of(const std::vector<Error>& errors, std::size_t omitted) {
  if (errors.empty()) throw std::logic_error("GcodeErrors without an error");
  std::string text = errors.front().message();
  for (std::size_t k = 1; k < errors.size(); ++k) text.append("\n").append(errors[k].what());
  if (omitted > 0) text.append(fmt::format("\n… and {} more", omitted));
  return text;
}

}  // namespace

GcodeErrors::GcodeErrors(std::vector<Error> errors, std::size_t omitted)
    : Error(errors.empty() ? SourceLocation{} : errors.front().where(), rest_of(errors, omitted)),
      errors_(std::move(errors)),
      omitted_(omitted) {}

}  // namespace stiffpath::motion
