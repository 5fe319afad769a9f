// Internal: the G-code modal state machine that turns one block into at most one path segment.
#pragma once

#include <optional>

#include "gcode_block.hpp"
#include "stiffpath/motion/gcode_reader.hpp"

namespace stiffpath::motion {

//! Modal state of a program and the rules that execute a block (RS274/NGC order: feed, power,
//! laser, units, path mode, distance mode, dwell, G92, motion, program end).
class GcodeInterpreter {
 public:
  explicit GcodeInterpreter(const GcodeOptions& options);

  //! Executes one block; returns the segment it produces, if any. Throws Error naming the word.
  std::optional<PathSegment> execute(const detail::GcodeBlock& block);
  [[nodiscard]] bool ended() const noexcept { return ended_; }

 private:
  void set_modes(const detail::GcodeBlock& block);
  std::optional<PathSegment> dwell(const detail::GcodeBlock& block);
  void set_offset(const detail::GcodeBlock& block);
  std::optional<PathSegment> move(const detail::GcodeBlock& block, const GcodeWord& anchor);
  Vec2 target(const detail::GcodeBlock& block) const;
  void decorate(PathSegment& segment, int line) const;

  GcodeOptions options_;
  double scale_m_ = 1e-3;          // program unit in m (G21 mm, G20 inch)
  bool incremental_ = false;       // G91
  int motion_ = -1;                // active motion code in tenths (0, 10, 20, 30); −1 none yet
  std::optional<double> feed_m_s_;
  double power_ = 0.0;             // S
  bool laser_ = false;             // M3/M4
  JunctionMode mode_;
  double blend_tolerance_m_;
  Vec2 offset_m_ = Vec2::Zero();   // G92 offset on top of the work offset
  std::optional<Vec2> position_m_;
  bool ended_ = false;
};

//! Builds the arc of a G2/G3 block from `start` to `end` (robot frame, m) with its I/J or R words
//! (gcode_arc.cpp). Throws Error naming the word for a missing centre, R with a full circle, a
//! radius too small for the chord, or an end point off the circle by more than the tolerance.
PathSegment build_arc(const detail::GcodeBlock& block, const GcodeWord& motion, bool clockwise, const Vec2& start,
                      const Vec2& end, double scale_m, double tolerance_m);

}  // namespace stiffpath::motion
