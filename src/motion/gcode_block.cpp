// Sorting a line's words into modal groups; every unsupported or duplicated word is an error naming it.
#include "gcode_block.hpp"

#include <cmath>
#include <string>

namespace stiffpath::motion::detail {

int code_tenths(double value) noexcept {
  const double tenths = value * 10.0;
  const double rounded = std::round(tenths);
  if (std::abs(tenths - rounded) > 1e-6 || rounded < 0.0 || rounded > 1e6) return -1;
  return static_cast<int>(rounded);
}

void GcodeBlock::fail(const GcodeWord& word, const std::string& message) const {
  throw Error(SourceLocation{where->file, where->line, word.column}, word_name(word) + ": " + message);
}

namespace {

void assign(const GcodeBlock& block, const GcodeWord*& slot, const GcodeWord& word, const char* group) {
  if (slot != nullptr) {
    block.fail(word, std::string("a second ") + group + " word on one line (" + word_name(*slot) + " at column " +
                         std::to_string(slot->column) + ")");
  }
  slot = &word;
}

const char* unsupported_g(int code) {
  switch (code) {
    case 180: case 190: return "only the XY plane (G17) is supported";
    case 410: case 411: case 420: case 421: return "cutter radius compensation is not supported";
    case 430: case 431: case 432: return "tool length compensation is not supported";
    case 730: case 760: case 810: case 820: case 830: case 840: case 850: case 860: case 870: case 880:
    case 890: return "canned cycles are not supported";
    case 550: case 560: case 570: case 580: case 590: case 591: case 592: case 593:
      return "only the G54 work offset is supported (its origin comes from the configuration)";
    case 930: case 950: return "only feed in units per minute (G94) is supported";
    case 280: case 300: return "homing moves are not supported";
    case 530: return "machine coordinates are not supported";
    case 901: case 911: return "arc centre modes are not supported (I and J are always relative to the start)";
    default: return "unsupported G code";
  }
}

void add_g(GcodeBlock& block, const GcodeWord& word) {
  const int code = code_tenths(word.value);
  switch (code) {
    case 0: case 10: case 20: case 30: assign(block, block.motion, word, "motion"); return;
    case 40: case 920: assign(block, block.non_modal, word, "non-modal (G4/G92)"); return;
    case 200: case 210: assign(block, block.units, word, "units (G20/G21)"); return;
    case 900: case 910: assign(block, block.distance, word, "distance mode (G90/G91)"); return;
    case 610: case 611: case 640: assign(block, block.path_mode, word, "path control (G61/G64)"); return;
    case 170: case 400: case 490: case 540: case 800: case 940: return;  // the defaults: nothing to do
    default: block.fail(word, unsupported_g(code));
  }
}

void add_m(GcodeBlock& block, const GcodeWord& word) {
  switch (code_tenths(word.value)) {
    case 30: case 40: case 50: assign(block, block.spindle, word, "laser (M3/M4/M5)"); return;
    case 20: case 300: assign(block, block.stop, word, "program end (M2/M30)"); return;
    case 70: case 80: case 90: return;  // coolant / air assist: no effect on the motion
    case 0: case 10: block.fail(word, "program pauses are not supported");
    case 60: block.fail(word, "tool changes are not supported");
    default: block.fail(word, "unsupported M code");
  }
}

void add_value(GcodeBlock& block, const GcodeWord*& slot, const GcodeWord& word) {
  if (slot != nullptr) {
    block.fail(word, std::string(1, word.letter) + " is given twice on one line (also at column " +
                         std::to_string(slot->column) + ")");
  }
  slot = &word;
}

}  // namespace

GcodeBlock parse_block(std::span<const GcodeWord> words, const SourceLocation& where) {
  GcodeBlock block;
  block.where = &where;
  for (const GcodeWord& word : words) {
    switch (word.letter) {
      case 'G': add_g(block, word); break;
      case 'M': add_m(block, word); break;
      case 'X': add_value(block, block.x, word); break;
      case 'Y': add_value(block, block.y, word); break;
      case 'I': add_value(block, block.i, word); break;
      case 'J': add_value(block, block.j, word); break;
      case 'R': add_value(block, block.r, word); break;
      case 'F': add_value(block, block.f, word); break;
      case 'S': add_value(block, block.s, word); break;
      case 'P': add_value(block, block.p, word); break;
      case 'N': break;  // line number
      case 'Z': block.fail(word, "the robot moves in the XY plane only (no Z axis)");
      case 'A': case 'B': case 'C': case 'U': case 'V': case 'W':
        block.fail(word, "only the X and Y axes exist");
      case 'K': block.fail(word, "arcs are in the XY plane; give their centre with I and J");
      case 'T': block.fail(word, "tool selection is not supported");
      case 'O': block.fail(word, "program numbers and subroutines are not supported");
      default: block.fail(word, "unsupported word");
    }
  }
  return block;
}

}  // namespace stiffpath::motion::detail
