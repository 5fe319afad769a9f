// Sorting a line's words into modal groups; every unsupported or duplicated word is a refusal naming it.
#include "gcode_block.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "stiffpath/motion/gcode_limits.hpp"

namespace stiffpath::motion::detail {

int code_tenths(double value) noexcept {
  const double tenths = value * 10.0;
  const double rounded = std::round(tenths);
  if (std::abs(tenths - rounded) > 1e-6 || rounded < 0.0 || rounded > 1e6) return -1;
  return static_cast<int>(rounded);
}

Error GcodeBlock::error(const GcodeWord& word, const std::string& message) const {
  return Error(SourceLocation{where->file, where->line, word.column}, word_name(word) + ": " + message);
}

void GcodeBlock::fail(const GcodeWord& word, const std::string& message) const { throw error(word, message); }

namespace {

// The words of one line being sorted, and the refusals found so far.
struct Sorter {
  GcodeBlock& block;
  bool strict;
  std::vector<Error>& refusals;
  std::size_t& omitted;
  std::span<const double> ignored_m_codes;

  [[nodiscard]] bool ignored(int code) const {
    return !strict && std::any_of(ignored_m_codes.begin(), ignored_m_codes.end(),
                                  [code](double m) { return code_tenths(m) == code; });
  }

  // Keeps the first refusals, counts the rest: a line of a million bad words costs no memory.
  void refuse(const GcodeWord& word, const std::string& message) {
    if (refusals.size() < max_reported_errors) {
      refusals.push_back(block.error(word, message));
    } else {
      ++omitted;
    }
  }

  void assign(const GcodeWord*& slot, const GcodeWord& word, const char* group) {
    if (slot != nullptr) {
      refuse(word, std::string("a second ") + group + " word on one line (" + word_name(*slot) + " at column " +
                       std::to_string(slot->column) + ")");
      return;
    }
    slot = &word;
  }

  void value(const GcodeWord*& slot, const GcodeWord& word) {
    if (slot != nullptr) {
      refuse(word, std::string(1, word.letter) + " is given twice on one line (also at column " +
                       std::to_string(slot->column) + ")");
      return;
    }
    slot = &word;
  }

  void g(const GcodeWord& word);
  void m(const GcodeWord& word);
  void word(const GcodeWord& word);
};

const char* unsupported_g(int code) {
  switch (code) {
    case 171: case 181: case 191: return "only the XY, XZ and YZ planes (G17, G18, G19) are supported";
    case 410: case 411: case 420: case 421: return "cutter radius compensation is not supported";
    case 730: case 760: case 810: case 820: case 830: case 840: case 850: case 860: case 870: case 880:
    case 890: return "canned cycles are not supported";
    case 550: case 560: case 570: case 580: case 590: case 591: case 592: case 593:
      return "only the G54 work offset is supported (its origin comes from the configuration)";
    case 930: case 950: return "only feed in units per minute (G94) is supported";
    case 281: case 301: return "the home position comes from the robot, not from the program";
    case 530: return "machine coordinates are not supported";
    case 901: return "arc centre modes are not supported (I and J are always relative to the start)";
    default: return "unsupported G code";
  }
}

void Sorter::g(const GcodeWord& w) {
  const int code = code_tenths(w.value);
  switch (code) {
    case 0: case 10: case 20: case 30: assign(block.motion, w, "motion"); return;
    case 40: case 920: assign(block.non_modal, w, "non-modal (G4/G28/G30/G92)"); return;
    case 280: case 300:
      if (strict) return refuse(w, "homing moves are not supported");
      assign(block.non_modal, w, "non-modal (G4/G28/G30/G92)");
      return;
    case 200: case 210: assign(block.units, w, "units (G20/G21)"); return;
    case 900: case 910: assign(block.distance, w, "distance mode (G90/G91)"); return;
    case 610: case 611: case 640: assign(block.path_mode, w, "path control (G61/G64)"); return;
    case 180: case 190:  // arcs in XZ / YZ: their XY projection
      if (strict) return refuse(w, "only the XY plane (G17) is supported");
      assign(block.plane, w, "plane (G17/G18/G19)");
      return;
    case 170: assign(block.plane, w, "plane (G17/G18/G19)"); return;
    case 430: case 431: case 432:  // tool length offsets: they only move Z
      if (strict) return refuse(w, "tool length compensation is not supported");
      assign(block.tool_length, w, "tool length (G43/G49)");
      return;
    case 400: case 490: case 540: case 800: case 940: return;  // the defaults: nothing to do
    case 911:  // incremental arc centres: what I and J always are
      if (strict) refuse(w, "arc centre modes are not supported (I and J are always relative to the start)");
      return;
    default: refuse(w, unsupported_g(code));
  }
}

void Sorter::m(const GcodeWord& w) {
  const int code = code_tenths(w.value);
  switch (code) {
    case 30: case 40: case 50: assign(block.laser, w, "laser (M3/M4/M5)"); return;
    case 1060: case 1070: case 620: case 630:
      if (strict) return refuse(w, "unsupported M code");
      assign(block.laser, w, "laser (M3/M4/M5/M106/M107/M62/M63)");
      return;
    case 20: case 300: assign(block.stop, w, "program end (M2/M30)"); return;
    case 70: case 80: case 90: return;  // coolant / air assist: no effect on the motion
    case 2040: assign(block.acceleration, w, "acceleration (M204)"); return;
    case 0: case 10:
      if (strict) return refuse(w, "program pauses are not supported");
      assign(block.pause, w, "program stop (M0/M1)");
      return;
    case 60:
      if (strict) return refuse(w, "tool changes are not supported");
      block.tool = true;
      return;
    default:
      if (ignored(code)) return;  // a vendor M-code that does nothing to the XY motion
      refuse(w, "unsupported M code");
  }
}

void Sorter::word(const GcodeWord& w) {
  switch (w.letter) {
    case 'G': g(w); break;
    case 'M': m(w); break;
    case 'X': value(block.x, w); break;
    case 'Y': value(block.y, w); break;
    case 'I': value(block.i, w); break;
    case 'J': value(block.j, w); break;
    case 'R': value(block.r, w); break;
    case 'K': value(block.k, w); break;
    case 'Q': value(block.q, w); break;
    case 'F': value(block.f, w); break;
    case 'S': value(block.s, w); break;
    case 'P': value(block.p, w); break;
    case 'N': break;  // line number
    case 'Z':
      if (strict) return refuse(w, "the robot moves in the XY plane only (no Z axis)");
      value(block.z, w);
      break;
    case 'T':
      if (strict) return refuse(w, "tool selection is not supported");
      block.tool = true;
      break;
    case 'O':
      if (strict) refuse(w, "program numbers and subroutines are not supported");
      break;  // a program number: nothing to do
    case 'H':
      if (strict) return refuse(w, "tool length offsets are not supported");
      if (block.tool_length == nullptr) block.tool_length = &w;
      break;
    case 'E': case 'L':
      if (block.ignored_m != nullptr) break;  // a parameter of the ignored M-code (M67 E0 Q50)
      refuse(w, "unsupported word");
      break;
    case 'A': case 'B': case 'C': case 'U': case 'V': case 'W': refuse(w, "only the X and Y axes exist"); break;
    default: refuse(w, "unsupported word");
  }
}

}  // namespace

GcodeBlock parse_block(std::span<const GcodeWord> words, const SourceLocation& where, bool strict,
                       std::span<const double> ignored_m_codes, std::vector<Error>& refusals, std::size_t& omitted) {
  GcodeBlock block;
  block.where = &where;
  Sorter sorter{block, strict, refusals, omitted, ignored_m_codes};
  // The ignored M-code first: its P, Q, E and L words may come before it on the line.
  for (const GcodeWord& word : words) {
    if (word.letter == 'M' && block.ignored_m == nullptr && sorter.ignored(code_tenths(word.value))) block.ignored_m = &word;
  }
  for (const GcodeWord& word : words) sorter.word(word);
  return block;
}

}  // namespace stiffpath::motion::detail
