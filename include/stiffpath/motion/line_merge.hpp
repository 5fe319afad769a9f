// Merging chains of short G64 lines that lie along a straight line within a tolerance (staircases, fine chords).
#pragma once

#include <deque>
#include <optional>

#include "stiffpath/motion/path_source.hpp"

namespace stiffpath::motion {

//! Longest line that is merged with its neighbours, in units of its merge tolerance ε: a line longer
//! than this is a move of its own (the drawing's), not a step of a staircase. 3ε takes a 0.01 mm
//! grid's diagonal steps (14.1 µm) at the default P = 0.01 mm (ε = 5 µm); finely flattened smooth
//! curves need no merging (their blends and fits already follow the curve), and keep their lines.
inline constexpr double merged_chord_tolerances = 3.0;

//! A path stage in front of the chord fitter and the corner blender (LinuxCNC's "naive CAM
//! detector", G64 Q). CAM output that rounds a vector to a grid (LaserWeb's 0.01 mm staircases) or
//! flattens a gentle curve finely turns at every vertex by up to 90°; each such corner would be
//! passed at a crawl. Consecutive lines merge into one while:
//! - each is a feed move (not G0) in blend mode with the same merge tolerance ε > 0
//!   (PathSegment::merge_tolerance_m: G64 Q, at most P/2), feed, laser state and power, and at most
//!   merged_chord_tolerances·ε long;
//! - every vertex passed lies within ε of the merged line (its direction within the intersection of
//!   the wedges asin(ε/D) around each vertex seen from the chain's start, at distance D), and every
//!   line of the chain moves forward along it (within 90° of it), so the vertices' projections onto
//!   it never fall.
//! Then the chain and the merged line are within ε of each other both ways (each point of either
//! lies within ε of the other), and each merged line (of two lines or more) carries a blend tolerance
//! of P − ε, so that the blended path stays within P of the program. O(1) work and memory per line.
//! The merged line carries the first line's source line and attributes.
class LineMerger final : public PathSource {
 public:
  explicit LineMerger(PathSource& source);
  std::optional<PathSegment> next() override;

  //! Lines in, lines out (after merging), over the program so far.
  [[nodiscard]] std::size_t lines_in() const noexcept { return lines_in_; }
  [[nodiscard]] std::size_t merged_out() const noexcept { return merged_out_; }

 private:
  [[nodiscard]] bool mergeable(const PathSegment& segment) const noexcept;
  bool extend(const PathSegment& segment) noexcept;
  void start(const PathSegment& segment) noexcept;
  void flush();

  PathSource& source_;
  std::optional<PathSegment> chain_;  // the first line of the chain, its end moved to the last vertex
  std::size_t chain_lines_ = 0;
  Vec2 reference_ = Vec2::UnitX();    // direction of the chain's first line: angles are measured from it
  double low_rad_ = 0.0, high_rad_ = 0.0;  // directions from the chain's start that keep every vertex within ε
  std::deque<PathSegment> ready_;
  std::size_t lines_in_ = 0, merged_out_ = 0;
  bool exhausted_ = false;
};

}  // namespace stiffpath::motion
