// What a G-code program was warned about (summarised by kind) and everything it was refused for (all at once).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "stiffpath/core/error.hpp"

namespace stiffpath::motion {

//! The kinds of warnings: each names something the reader accepted but did differently from, or
//! without, what the program literally asks. docs/motion.md lists them.
enum class GcodeWarningKind : std::uint8_t {
  z_ignored,            //!< Z words: the robot has no Z axis; a move with only Z takes no time
  tool_ignored,         //!< T words and M6
  program_stop,         //!< M0/M1: a rest (pause) or a dwell, as GcodeOptions::program_stop_dwell_s says
  block_delete,         //!< lines starting with '/': run or skipped per GcodeOptions::skip_block_delete
  power_clamped,        //!< S above the full scale: clamped to full power
  laser_without_power,  //!< a feed move with M3/M4 on and S 0: the laser does not fire
  long_dwell,           //!< a dwell over long_dwell_warning_s
  fan_as_laser,         //!< M106/M107 (Marlin fan output) read as laser on/off
  output_as_laser,      //!< M62/M63 (synchronised digital output) read as laser on/off
  output_ignored,       //!< M62/M63 or M106/M107 on an output configured as not the laser (GcodeOptions::outputs)
  tool_length_ignored,  //!< G43, G43.1, G43.2 and H words: tool length offsets only concern Z
  plane_arc_as_line,    //!< a G2/G3 arc in the XZ (G18) or YZ (G19) plane: its XY projection, a straight line
  m_code_ignored,       //!< a vendor M-code of GcodeOptions::ignored_m_codes (M100, M17, M18, …)
  start_at_home,        //!< G92 before the first move without a start position: the robot starts at its home
};

//! A short stable name of a kind ("z_ignored", …), the JSON key of a warning.
const char* to_string(GcodeWarningKind kind) noexcept;

//! One kind of warning over a whole program: what was done, on how many lines, the first of them.
struct GcodeWarning {
  GcodeWarningKind kind = GcodeWarningKind::z_ignored;
  std::string message;     //!< one sentence, from the first occurrence
  std::size_t count = 0;   //!< lines it happened on
  int first_line = 0;      //!< 1-based
};

//! Collects warnings, one entry per kind in order of first appearance.
class GcodeWarnings {
 public:
  //! Counts one more line of `kind`; the message is kept from the first.
  void add(GcodeWarningKind kind, int line, const std::string& message);
  [[nodiscard]] const std::vector<GcodeWarning>& list() const noexcept { return list_; }
  [[nodiscard]] bool empty() const noexcept { return list_.empty(); }

 private:
  std::vector<GcodeWarning> list_;
};

//! "file:line: message (N lines, the first shown)" for one summarised warning.
std::string describe(const GcodeWarning& warning, const std::string& file);

//! Every refusal of one program: the first max_reported_errors, in file order, and how many more.
//! what() holds one "file:line:column: WORD: reason" per line, then "… and N more" if any were left
//! out; where() is the first refusal's location.
class GcodeErrors : public Error {
 public:
  GcodeErrors(std::vector<Error> errors, std::size_t omitted);
  [[nodiscard]] const std::vector<Error>& errors() const noexcept { return errors_; }
  [[nodiscard]] std::size_t omitted() const noexcept { return omitted_; }

 private:
  std::vector<Error> errors_;
  std::size_t omitted_ = 0;
};

}  // namespace stiffpath::motion
