// Streaming G-code reader: a program file, line by line, into path segments in the robot frame.
#pragma once

#include <filesystem>
#include <fstream>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/motion/gcode_lexer.hpp"
#include "stiffpath/motion/path_source.hpp"

namespace stiffpath::motion {

//! Configuration of the interpreter: what the program does not say itself. Documented defaults.
struct GcodeOptions {
  //! Origin of G54 (the program's coordinates) in the robot frame (m). Default (0, 0): programs are
  //! written in the robot frame, whose workspace is x ∈ [172.132, 272.132] mm, y ∈ [−75, 75] mm.
  Vec2 work_offset_m = Vec2::Zero();
  //! Where the robot stands when the program starts (robot frame, m). When unset, the robot is
  //! assumed to be at the first absolute move's target, so that move takes no time.
  std::optional<Vec2> start_position_m;
  //! Path control before the program's first G61/G64: exact stop, so corners are never rounded
  //! unless the program asks for it.
  JunctionMode initial_mode = JunctionMode::exact_stop;
  //! Blend tolerance of a G64 without P (m): 10 µm.
  double default_blend_tolerance_m = 10e-6;
  //! How far an arc's end may be off its circle (m); also 0.1 % of the radius, whichever is larger.
  double arc_tolerance_m = 5e-6;
};

class GcodeInterpreter;

//! Reads a G-code program one line at a time and hands out its moves and dwells as PathSegments
//! (SI, robot frame). The dialect: G0 G1 G2 G3 (I/J or R, full circles) G4 G17 G20 G21 G54 G61
//! G61.1 G64 P G90 G91 G92, F (units/min), S, M3 M4 M5 M2 M30; G40 G49 G80 G94 M7 M8 M9 are
//! accepted and do nothing; comments in parentheses and after ';', N numbers, '%' lines. Anything
//! else throws stiffpath::Error "file:line:column: WORD: reason". Reading stops at M2/M30.
class GcodeReader final : public PathSource {
 public:
  //! Opens a file; its path (as given) names it in errors. Throws Error if it cannot be opened.
  explicit GcodeReader(const std::filesystem::path& path, GcodeOptions options = {});
  //! Reads from a stream (kept by reference); `label` names it in errors.
  GcodeReader(std::istream& in, std::string label, GcodeOptions options = {});
  ~GcodeReader() override;
  GcodeReader(const GcodeReader&) = delete;
  GcodeReader& operator=(const GcodeReader&) = delete;

  //! The next segment (zero-length moves are dropped), or nullopt after the last line or M2/M30.
  std::optional<PathSegment> next() override;
  //! Lines read so far (the line of the last segment handed out, or of the end).
  [[nodiscard]] int lines_read() const noexcept { return line_; }
  [[nodiscard]] const std::string& label() const noexcept { return label_; }

 private:
  std::unique_ptr<std::ifstream> owned_;
  std::istream* in_;
  std::string label_;
  std::unique_ptr<GcodeInterpreter> interpreter_;
  SourceLocation where_;  // file and current line, for errors
  std::string text_;
  std::vector<GcodeWord> words_;
  int line_ = 0;
};

}  // namespace stiffpath::motion
