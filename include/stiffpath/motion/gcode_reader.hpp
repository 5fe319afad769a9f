// Streaming G-code reader: a program file, line by line, into path segments in the robot frame.
#pragma once

#include <cstdint>
#include <deque>
#include <filesystem>
#include <fstream>
#include <functional>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/motion/gcode_diagnostics.hpp"
#include "stiffpath/motion/gcode_lexer.hpp"
#include "stiffpath/motion/gcode_limits.hpp"
#include "stiffpath/motion/path_source.hpp"

namespace stiffpath::motion {

//! Units of the P word of G4: seconds (RS274/NGC, LinuxCNC, GRBL) or milliseconds (Marlin, RepRapFirmware).
enum class DwellUnits : std::uint8_t { seconds, milliseconds };

//! The outputs a program switches: LinuxCNC's synchronised digital outputs (M62/M63 P n) and
//! Marlin's fans (M106/M107, P n the fan's index, 0 without P).
enum class OutputKind : std::uint8_t { digital, fan };
//! What an output drives: the laser (its on/off switches the laser), or something else (an LED, a
//! fan, a clamp): then its words are ignored with a warning.
enum class OutputRole : std::uint8_t { laser, ignored };
//! One output's role; outputs not listed in GcodeOptions::outputs drive the laser.
struct OutputAssignment {
  OutputKind kind = OutputKind::digital;
  int number = 0;  //!< P (0 ... 1000)
  OutputRole role = OutputRole::laser;
};

//! The vendor M-codes ignored by default (with a warning), because they do nothing to the XY motion:
//! M100 (a user M-code: an air-assist compressor), M17/M18 (steppers on/off), M52 (adaptive feed),
//! M65 (an immediate digital output off), M67/M68 (analog outputs).
inline const std::vector<double>& default_ignored_m_codes() {
  static const std::vector<double> codes{100, 17, 18, 52, 65, 67, 68};
  return codes;
}

//! Configuration of the interpreter: what the program does not say itself. Documented defaults.
struct GcodeOptions {
  //! Origin of G54 (the program's coordinates) in the robot frame (m). Default (0, 0): programs are
  //! written in the robot frame, whose workspace is x ∈ [172.132, 272.132] mm, y ∈ [−75, 75] mm.
  Vec2 work_offset_m = Vec2::Zero();
  //! Where the robot stands when the program starts (robot frame, m). When unset, the robot is
  //! assumed to be at the first absolute move's target, so that move takes no time.
  std::optional<Vec2> start_position_m;
  //! Where G28 and G30 send the robot (robot frame, m), e.g. the robot file's home position.
  //! When unset, a G28/G30 that moves X or Y is refused (one that only names Z is not).
  std::optional<Vec2> home_position_m;
  //! Path control before the program's first G61/G64: blending within default_blend_tolerance_m, as
  //! GRBL and Marlin (junction deviation 0.01-0.013 mm) and LinuxCNC (G64) run a program that names no
  //! mode; JunctionMode::exact_stop stops at every corner of such a program (`--blend off`).
  JunctionMode initial_mode = JunctionMode::blend;
  //! Blend tolerance of a G64 without P, and of a program that names no mode (m): 20 µm. Half of it
  //! may merge short lines (LineMerger): 10 µm is what straightens the staircases of coordinates
  //! written with two decimals (LaserWeb), whose vertices lie up to half a 0.01 mm step off the curve
  //! on either side (docs/motion.md, measured).
  double default_blend_tolerance_m = motion::default_blend_tolerance_m;
  //! How far an arc's end may be off its circle (m); also 0.1 % of the radius, whichever is larger.
  double arc_tolerance_m = 5e-6;
  //! Refuse what the strict RS274 subset does not have (Z, T, M6, O, M0/M1, G28/G30, G91.1,
  //! M106/M107, M62/M63, block delete, a byte-order mark, the DOS end-of-file character, nested
  //! comments) instead of accepting it with the documented mapping and a warning.
  bool strict = false;
  //! Units of G4 P. Default seconds (LinuxCNC, GRBL); Marlin and RepRapFirmware use milliseconds.
  DwellUnits dwell_p_units = DwellUnits::seconds;
  //! The S value of full laser power (M3/M4); power = min(S, s_max) / s_max. Default 1000 (GRBL $30).
  double s_max = default_s_max;
  //! M0/M1: unset (default) the robot comes to rest there and the job goes on at once (a pause the
  //! operator must make); set, a dwell of this many seconds (laser off) at that point.
  std::optional<double> program_stop_dwell_s;
  //! Lines starting with '/': false (default, the block-delete switch off) they run; true, they are skipped.
  bool skip_block_delete = false;
  //! M-codes accepted and ignored with a warning (m_code_ignored), with the P, Q, E and L words of their
  //! line; every other unknown M-code is refused. Numbers as written (100 for M100, 1.5 for M1.5).
  std::vector<double> ignored_m_codes = default_ignored_m_codes();
  //! What M62/M63 and M106/M107 switch, output by output; an output not listed drives the laser.
  std::vector<OutputAssignment> outputs;
  //! Called once with the warnings when the program has been read to its end without refusals.
  std::function<void(const std::string& file, const std::vector<GcodeWarning>&)> on_warnings;
};

//! Throws stiffpath::Error naming the field unless every option is finite and within the limits of
//! gcode_limits.hpp (offsets and positions within max_coordinate_m, s_max positive, the stop dwell
//! within max_block_duration_s, tolerances non-negative, M-codes and output numbers 0 ... 1000).
void validate(const GcodeOptions& options);

class GcodeInterpreter;

//! Reads a G-code program one line at a time and hands out its moves and dwells as PathSegments
//! (SI, robot frame). The dialect (docs/motion.md lists every word, its mapping and its warning):
//! G0 G1 G2 G3 (I/J or R, full circles) G4 G17 G18 G19 G20 G21 G28 G30 G43 G54 G61 G61.1 G64 P Q
//! G90 G91 G91.1 G92, F (units/min), S, M3 M4 (dynamic power) M5 M106 M107 M62 M63 M0 M1 M2 M30 M6,
//! T, H, Z, O, the ignored M-codes; G40 G49 G80 G94 M7 M8 M9 are accepted and do nothing; comments
//! in (nested) parentheses and after ';', N numbers, '%' lines, block delete, a byte-order mark, the
//! DOS end-of-file character. GcodeOptions::strict refuses the additions. A refused line is
//! remembered and reading goes on to the end of the file without handing out anything more; then
//! all refusals are thrown together as GcodeErrors (each "file:line:column: WORD: reason"). Reading
//! stops at M2/M30, and at a line longer than max_line_bytes (refused). 
class GcodeReader final : public PathSource {
 public:
  //! Opens a file; its path (as given) names it in errors. Throws Error if it cannot be opened or
  //! the options are out of range.
  explicit GcodeReader(const std::filesystem::path& path, GcodeOptions options = {});
  //! Reads from a stream (kept by reference); `label` names it in errors.
  GcodeReader(std::istream& in, std::string label, GcodeOptions options = {});
  ~GcodeReader() override;
  GcodeReader(const GcodeReader&) = delete;
  GcodeReader& operator=(const GcodeReader&) = delete;

  //! The next segment (zero-length moves are dropped), or nullopt after the last line or M2/M30.
  //! Throws GcodeErrors at the end of the file if any line was refused.
  std::optional<PathSegment> next() override;
  //! Lines read so far (the line of the last segment handed out, or of the end).
  [[nodiscard]] int lines_read() const noexcept { return line_; }
  [[nodiscard]] const std::string& label() const noexcept { return label_; }
  //! The warnings so far, one per kind (complete once next() has returned nullopt).
  [[nodiscard]] const std::vector<GcodeWarning>& warnings() const noexcept { return warnings_.list(); }

 private:
  bool next_line();
  bool read_line();
  void refuse(const Error& error);

  std::unique_ptr<std::ifstream> owned_;
  std::istream* in_;
  std::string label_;
  GcodeOptions options_;
  GcodeWarnings warnings_;
  std::unique_ptr<GcodeInterpreter> interpreter_;
  SourceLocation where_;  // file and current line, for errors
  std::string text_;
  std::string buffer_;   // the raw line, at most max_line_bytes + 1 bytes
  std::vector<GcodeWord> words_;
  std::vector<Error> line_refusals_;  // the current line's (at most max_reported_errors)
  std::deque<PathSegment> pending_;  // segments of the current line not yet handed out
  std::vector<Error> errors_;
  std::size_t omitted_errors_ = 0;
  int line_ = 0;
  bool end_of_file_ = false;  // a DOS end-of-file character was read
  bool finished_ = false;
};

}  // namespace stiffpath::motion
