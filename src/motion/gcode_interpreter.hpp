// Internal: the G-code modal state machine that turns one block into path segments.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>

#include "gcode_block.hpp"
#include "stiffpath/motion/gcode_reader.hpp"

namespace stiffpath::motion {

//! Modal state of a program and the rules that execute a block (RS274/NGC order: units, feed,
//! power, tool, laser, path mode, distance mode, dwell, G28/G30 or G92, motion, stop, program end).
class GcodeInterpreter {
 public:
  GcodeInterpreter(const GcodeOptions& options, GcodeWarnings& warnings);

  //! Executes one block, appending the segments it produces (none, one, or two for a G28 through
  //! an intermediate point, plus a stop) to `out`. Throws Error naming the word.
  void execute(const detail::GcodeBlock& block, std::deque<PathSegment>& out);
  //! At the end of the program: the dwells that waited for a position (a program that never moves
  //! but has a start or home position dwells there; otherwise they are dropped with the program's
  //! lack of motion).
  void finish(std::deque<PathSegment>& out);
  [[nodiscard]] bool ended() const noexcept { return ended_; }

 private:
  enum class Laser : std::uint8_t { off, s_word, fixed };  // off; M3/M4 (power from S); M106/M62

  void set_feed(const detail::GcodeBlock& block);
  void set_laser(const detail::GcodeBlock& block);
  void set_modes(const detail::GcodeBlock& block);
  void dwell(const detail::GcodeBlock& block, std::deque<PathSegment>& out);
  void set_offset(const detail::GcodeBlock& block, std::deque<PathSegment>& out);
  //! The robot's position becomes known: the dwells programmed before it take their time there.
  void locate(const Vec2& position_m, std::deque<PathSegment>& out);
  //! What an output word (M62/M63 P, M106/M107 P) switches: true for the laser.
  [[nodiscard]] bool drives_laser(OutputKind kind, const detail::GcodeBlock& block) const;
  void home(const detail::GcodeBlock& block, std::deque<PathSegment>& out);
  void move(const detail::GcodeBlock& block, const GcodeWord& anchor, std::deque<PathSegment>& out);
  void rapid_to(const Vec2& end, const detail::GcodeBlock& block, std::deque<PathSegment>& out);
  void program_stop(const detail::GcodeBlock& block, std::deque<PathSegment>& out);
  void require_start(const detail::GcodeBlock& block, const GcodeWord& anchor) const;
  Vec2 target(const detail::GcodeBlock& block) const;
  //! An X or Y word in m (units applied), refused beyond ±max_coordinate_mm at the word.
  double coordinate_m(const detail::GcodeBlock& block, const GcodeWord& word) const;
  [[nodiscard]] double power_fraction() const noexcept;
  void set_acceleration(const detail::GcodeBlock& block);
  void emit(PathSegment segment, const detail::GcodeBlock& block, std::deque<PathSegment>& out);
  void warn(GcodeWarningKind kind, const detail::GcodeBlock& block, const std::string& message);

  GcodeOptions options_;
  GcodeWarnings& warnings_;
  double scale_m_ = 1e-3;          // program unit in m (G21 mm, G20 inch)
  bool incremental_ = false;       // G91
  int motion_ = -1;                // active motion code in tenths (0, 10, 20, 30); −1 none yet
  std::optional<double> feed_m_s_;
  double acceleration_m_s2_ = 0.0;  // M204 S (0: the machine's limit)
  double s_ = 0.0;                 // S as programmed
  Laser laser_ = Laser::off;
  bool dynamic_ = false;           // M4
  double fixed_power_ = 0.0;       // M106 S / 255, or 1 for M62
  JunctionMode mode_;
  double blend_tolerance_m_;
  double merge_tolerance_m_;       // G64 Q, at most half of P (PathSegment::merge_tolerance_m)
  int plane_ = 170;                // G17, G18, G19 in tenths
  std::deque<PathSegment> waiting_;  // dwells before the position is known, without their point
  Vec2 offset_m_ = Vec2::Zero();   // G92 offset on top of the work offset
  std::optional<Vec2> position_m_;
  bool ended_ = false;
};

//! Builds the arc of a G2/G3 block from `start` to `end` (robot frame, m) with its I/J or R words
//! (gcode_arc.cpp). Throws Error naming the word for a missing centre, R with a full circle, a
//! radius too small for the chord, an end point off the circle by more than the tolerance, I, J, R
//! or a radius beyond max_arc_radius_m, or an arc reaching beyond max_coordinate_m.
PathSegment build_arc(const detail::GcodeBlock& block, const GcodeWord& motion, bool clockwise, const Vec2& start,
                      const Vec2& end, double scale_m, double tolerance_m);

}  // namespace stiffpath::motion
