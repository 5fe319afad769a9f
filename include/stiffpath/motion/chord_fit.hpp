// Fitting chord-flattened curves under G64: chains of short lines become a tangent chain of biarcs within P.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "stiffpath/motion/path_source.hpp"

namespace stiffpath::motion {

//! Which chains of G64 chords the ChordFitter fits: none, only chains of merged lines (LineMerger's:
//! a staircase or fine chords straightened within part of P, `--chords auto`), or every chain
//! (`--chords fit`).
enum class ChordFitting : std::uint8_t { none, merged, all };

//! Longest chain of chords fitted at once; a longer chain is fitted in pieces joined at a chord's
//! midpoint (tangent there, with a curvature step like any stretch end).
inline constexpr std::size_t max_fitted_chain = 4096;

//! A path stage in front of the corner blender. CAM programs flatten curves into many short lines;
//! the blender's G64 arcs make them tangent but concentrate each vertex's turn in its own arcs, so
//! the curvature steps at every chord, and the junction rule (v²·Δκ ≤ j·τ) bounds the speed there.
//! This stage replaces such a chain by a curve whose curvature follows the curve the chords were cut
//! from:
//! - a chain: consecutive lines, not G0, the first of each pair in G64 with P > 0, same laser
//!   state, turning by at most 45° and differing in length by at most 4×, each at least 1 µm long;
//! - at each inner vertex v_i: a local polynomial fitted to v_i and up to 3 neighbours on each side
//!   (the parabola through three, a least-squares cubic through more while it fits them to P/20)
//!   gives the curve's point, curvature κ_i and tangent t_i; the curve passes q_i, that point moved
//!   towards the centre of curvature by half the chords' mean sagitta s = κ·L²/8 (at most P), so that
//!   it lies about s/2 from the chords' midpoints and s/2 from the vertices;
//! - between q_i and q_{i+1}: a biarc with the tangents t_i, t_{i+1} (G1 everywhere; for points on a
//!   circle both arcs are that circle's concentric, and on a smooth curve neighbouring arcs' curvatures
//!   differ by about κ′·L/2);
//! - at a chain's ends: the first chord stays a line up to one arc that leaves it tangentially and
//!   reaches q_1 along t_1 (or, where that arc does not fit, a line to the chord's midpoint and a
//!   biarc from there); likewise at the end;
//! - every piece is checked at 9 points to lie within its chord's P of the chord; where one does not
//!   (the chords too coarse for P: s > 2P, or a true corner), the chord's vertices are left as
//!   corners for the blender's fillets.
//! Each piece carries its chord's feed, laser power, source line and mode. Holds one chain.
class ChordFitter final : public PathSource {
 public:
  //! `merged_only`: a chain holds only merged lines (PathSegment::merged), ChordFitting::merged.
  explicit ChordFitter(PathSource& source, bool merged_only = false);
  std::optional<PathSegment> next() override;

 private:
  //! Fits chain_ into ready_; `ends_mid`: the chain stops at its last chord's midpoint (the next
  //! chain starts there).
  void fit_chain(bool ends_mid);

  PathSource& source_;
  bool merged_only_ = false;
  std::vector<PathSegment> chain_;
  bool chain_starts_mid_ = false;  // the first chord's first half was emitted with the chain before
  std::deque<PathSegment> ready_;
  bool exhausted_ = false;
};

}  // namespace stiffpath::motion
