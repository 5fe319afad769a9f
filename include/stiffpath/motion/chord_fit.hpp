// Fitting chord-flattened curves under G64: chains of short lines become a tangent chain of biarcs within P.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

#include "stiffpath/motion/path_source.hpp"

namespace stiffpath::motion {

//! Longest chain of chords fitted at once; a longer chain is fitted in pieces joined at a chord's
//! midpoint (tangent there, with a curvature step like any stretch end).
inline constexpr std::size_t max_fitted_chain = 4096;

//! A path stage in front of the corner blender. CAM programs flatten curves into many short lines;
//! fillets at their vertices (the blender's G64) make them tangent but leave pieces of line between
//! the fillets, so the curvature jumps between 0 and 1/r at every chord, and the junction rule
//! (v²·Δκ ≤ j·τ) holds the speed far below the feed. This stage replaces such a chain by a curve
//! whose curvature follows the curve the chords were cut from:
//! - a chain: consecutive lines, not G0, the first of each pair in G64 with P > 0, same laser
//!   state, turning by at most 45° and differing in length by at most 4×, each at least 1 µm long;
//! - at each inner vertex v_i: the circle through v_{i−1}, v_i, v_{i+1} gives the curvature κ_i and
//!   the tangent t_i; the curve passes q_i = v_i moved towards the circle's centre by half the
//!   chords' mean sagitta s = κ·L²/8 (at most P), so that it lies about s/2 from the chords'
//!   midpoints and s/2 from the vertices;
//! - between q_i and q_{i+1}: a biarc with the tangents t_i, t_{i+1} (G1 everywhere; for points on a
//!   circle both arcs are that circle's concentric, and on a smooth curve neighbouring arcs' curvatures
//!   differ by about κ′·L/2);
//! - at a chain's ends: the first chord's first half stays a line, then a biarc from its midpoint
//!   (along the chord) to q_1; likewise at the end;
//! - every piece is checked at 9 points to lie within its chord's P of the chord; where one does not
//!   (the chords too coarse for P: s > 2P, or a true corner), the chord's vertices are left as
//!   corners for the blender's fillets.
//! Each piece carries its chord's feed, laser power, source line and mode. Holds one chain.
class ChordFitter final : public PathSource {
 public:
  explicit ChordFitter(PathSource& source);
  std::optional<PathSegment> next() override;

 private:
  //! Fits chain_ into ready_; `ends_mid`: the chain stops at its last chord's midpoint (the next
  //! chain starts there).
  void fit_chain(bool ends_mid);

  PathSource& source_;
  std::vector<PathSegment> chain_;
  bool chain_starts_mid_ = false;  // the first chord's first half was emitted with the chain before
  std::deque<PathSegment> ready_;
  bool exhausted_ = false;
};

}  // namespace stiffpath::motion
