// Internal: one G-code line's words sorted into modal groups and value words, with the line's checks.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "stiffpath/core/error.hpp"
#include "stiffpath/motion/gcode_lexer.hpp"

namespace stiffpath::motion::detail {

//! A G or M number in tenths (G61.1 → 611), or −1 when it has more than one decimal.
int code_tenths(double value) noexcept;

//! The words of one line by role; null where absent. Pointers into the lexer's word vector.
struct GcodeBlock {
  const GcodeWord* motion = nullptr;      //!< G0, G1, G2, G3
  const GcodeWord* non_modal = nullptr;   //!< G4 (dwell), G28/G30 (home), G92 (coordinate offset)
  const GcodeWord* plane = nullptr;       //!< G17, G18, G19
  const GcodeWord* units = nullptr;       //!< G20, G21
  const GcodeWord* distance = nullptr;    //!< G90, G91
  const GcodeWord* path_mode = nullptr;   //!< G61, G61.1, G64
  const GcodeWord* laser = nullptr;       //!< M3, M4, M5, M106, M107, M62, M63
  const GcodeWord* stop = nullptr;        //!< M2, M30
  const GcodeWord* pause = nullptr;       //!< M0, M1
  const GcodeWord* acceleration = nullptr;  //!< M204 (its S is the acceleration, not the laser's power)
  const GcodeWord* x = nullptr;
  const GcodeWord* y = nullptr;
  const GcodeWord* z = nullptr;           //!< read only to tell a move with Z from a line without one
  const GcodeWord* i = nullptr;
  const GcodeWord* j = nullptr;
  const GcodeWord* r = nullptr;
  const GcodeWord* k = nullptr;           //!< an arc's centre in Z: only for G18/G19 arcs (the interpreter checks)
  const GcodeWord* q = nullptr;           //!< G64 Q: the tolerance for merging short lines
  const GcodeWord* f = nullptr;
  const GcodeWord* s = nullptr;
  const GcodeWord* p = nullptr;
  bool tool = false;                      //!< a T word or M6 (ignored)
  const GcodeWord* tool_length = nullptr; //!< G43, G43.1, G43.2 or an H word (ignored)
  const GcodeWord* ignored_m = nullptr;   //!< an M-code of GcodeOptions::ignored_m_codes (ignored, with its P/Q/E/L)
  const SourceLocation* where = nullptr;  //!< file and line (column 0); outlives the block

  //! The Error at the word's column: "<word>: message".
  [[nodiscard]] Error error(const GcodeWord& word, const std::string& message) const;
  //! Throws error(word, message).
  [[noreturn]] void fail(const GcodeWord& word, const std::string& message) const;
  [[nodiscard]] bool has_axis() const noexcept { return x != nullptr || y != nullptr; }
};

//! Sorts the words. Every unsupported or duplicated word (a second motion word, two words of one
//! modal group, an axis given twice, cutter compensation, canned cycles …, and in `strict` mode Z,
//! T, H, O, M6, M0/M1, G28/G30, G43, G91.1, M106/M107, M62/M63, the ignored M-codes) is a refusal,
//! one per word: the first up to max_reported_errors − refusals.size() are appended to `refusals`,
//! the others only counted in `omitted`. The block is only meant to be executed when none was found.
//! `ignored_m_codes`: GcodeOptions::ignored_m_codes.
GcodeBlock parse_block(std::span<const GcodeWord> words, const SourceLocation& where, bool strict,
                       std::span<const double> ignored_m_codes, std::vector<Error>& refusals, std::size_t& omitted);

}  // namespace stiffpath::motion::detail
