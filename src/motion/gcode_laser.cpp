// The laser words of the G-code dialect: S, M3/M4 (constant and dynamic power), M5, and M106/M107, M62/M63 mapped to laser on/off.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "gcode_interpreter.hpp"

namespace stiffpath::motion {

using detail::code_tenths;
using detail::GcodeBlock;

namespace {
const char* const fan_message = "M106/M107 (Marlin's fan output) are read as laser on/off, M106 S 0-255 as the power";
const char* const output_message = "M62/M63 (synchronised digital output) are read as laser on at full power/off";
}  // namespace

bool GcodeInterpreter::drives_laser(OutputKind kind, const GcodeBlock& b) const {
  const int number = b.p != nullptr ? static_cast<int>(std::lround(b.p->value)) : 0;
  if (b.p != nullptr && (b.p->value < 0.0 || b.p->value != std::round(b.p->value))) {
    b.fail(*b.p, "an output number is a whole number, 0 or more");
  }
  for (const OutputAssignment& output : options_.outputs) {
    if (output.kind == kind && output.number == number) return output.role == OutputRole::laser;
  }
  return true;  // unlisted outputs drive the laser
}

void GcodeInterpreter::set_laser(const GcodeBlock& b) {
  int code = b.laser != nullptr ? code_tenths(b.laser->value) : -1;
  const bool fan = code == 1060 || code == 1070, output = code == 620 || code == 630;
  if ((fan || output) && !drives_laser(fan ? OutputKind::fan : OutputKind::digital, b)) {
    warn(GcodeWarningKind::output_ignored, b,
         fmt::format("M62/M63 and M106/M107 of outputs configured as not the laser are ignored (here {} P{})",
                     word_name(*b.laser), b.p != nullptr ? b.p->value : 0.0));
    if (fan) {  // the S of an ignored fan is the fan's, not the laser's
      if (b.s != nullptr && b.s->value < 0.0) b.fail(*b.s, "fan speed must not be negative");
      return;
    }
    code = -1;  // an ignored digital output: an S on its line is still the laser's
  }
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
