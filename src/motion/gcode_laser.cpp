// The laser words of the G-code dialect: S, M3/M4 (constant and dynamic power), M5, and M106/M107, M62/M63 mapped to laser on/off.
#include <algorithm>
#include <fmt/format.h>

#include "gcode_interpreter.hpp"

namespace stiffpath::motion {

using detail::code_tenths;
using detail::GcodeBlock;

namespace {
const char* const fan_message = "M106/M107 (Marlin's fan output) are read as laser on/off, M106 S 0-255 as the power";
const char* const output_message = "M62/M63 (synchronised digital output) are read as laser on at full power/off";
}  // namespace

void GcodeInterpreter::set_laser(const GcodeBlock& b) {
  const int code = b.laser != nullptr ? code_tenths(b.laser->value) : -1;
  if (b.s != nullptr && b.acceleration == nullptr) {  // with M204 the S word is its acceleration
    if (b.s->value < 0.0) b.fail(*b.s, "laser power must not be negative");
    const double full = code == 1060 ? fan_s_max : options_.s_max;
    if (b.s->value > full) {
      warn(GcodeWarningKind::power_clamped, b, fmt::format("S above the full scale {:g} is clamped to full power", full));
    }
    if (code == 1060) {
      fixed_power_ = std::min(b.s->value, fan_s_max) / fan_s_max;  // M106's own S, not the laser's
    } else {
      s_ = b.s->value;
    }
  } else if (code == 1060) {
    fixed_power_ = 1.0;  // M106 without S: full output
  }
  switch (code) {
    case 30: case 40: laser_ = Laser::s_word; dynamic_ = code == 40; break;
    case 1060:
      laser_ = Laser::fixed;
      dynamic_ = false;
      warn(GcodeWarningKind::fan_as_laser, b, fan_message);
      break;
    case 620:
      laser_ = Laser::fixed;
      dynamic_ = false;
      fixed_power_ = 1.0;
      warn(GcodeWarningKind::output_as_laser, b, output_message);
      break;
    case 1070:
      laser_ = Laser::off;
      warn(GcodeWarningKind::fan_as_laser, b, fan_message);
      break;
    case 630:
      laser_ = Laser::off;
      warn(GcodeWarningKind::output_as_laser, b, output_message);
      break;
    case 50: laser_ = Laser::off; break;
    default: break;
  }
}

double GcodeInterpreter::power_fraction() const noexcept {
  switch (laser_) {
    case Laser::s_word: return std::min(s_, options_.s_max) / options_.s_max;
    case Laser::fixed: return fixed_power_;
    case Laser::off: return 0.0;
  }
  return 0.0;
}

}  // namespace stiffpath::motion
