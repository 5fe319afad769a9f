// G64 corner rounding: a tangent arc between two lines, within the program's blend tolerance.
#pragma once

#include <array>
#include <deque>
#include <memory>
#include <optional>

#include "stiffpath/motion/chord_fit.hpp"
#include "stiffpath/motion/corner_choice.hpp"
#include "stiffpath/motion/path_source.hpp"

namespace stiffpath::motion {

//! The fillet that rounds the corner between two lines meeting at `corner_m` with unit directions
//! `in` and `out` (turn angle φ). The arc touches both lines at distance d = r·tan(φ/2) from the
//! corner and passes the corner at r·(1/cos(φ/2) − 1) ≤ tolerance; d is at most `max_trim_m`.
struct CornerFillet {
  Vec2 entry_m = Vec2::Zero();   //!< where the arc leaves the first line
  Vec2 exit_m = Vec2::Zero();    //!< where it joins the second line
  Vec2 center_m = Vec2::Zero();
  double radius_m = 0.0;
  double sweep_rad = 0.0;        //!< signed: > 0 for a left turn
  double trim_m = 0.0;           //!< d: how much each line loses
};

//! The fillet, or nullopt when the turn is a reversal (φ ≈ π) or the tolerance or room is zero.
std::optional<CornerFillet> corner_fillet(const Vec2& corner_m, const Vec2& in, const Vec2& out, double tolerance_m,
                                          double max_trim_m) noexcept;

//! The arc that replaces a line of direction `in` from line_start_m to the fillet's entry together
//! with the fillet: it starts at the line's start and ends at the fillet's exit, tangent there, so
//! it turns away from `in` at its start by about length·curvature. nullopt when that kink exceeds
//! max_kink_rad. Used for the remnants (a few nm to µm) that two blends leave of a chord.
std::optional<PathSegment> arc_absorbing_line(const Vec2& line_start_m, const Vec2& in, const CornerFillet& fillet,
                                              double max_kink_rad) noexcept;

//! The biarc (biarc.hpp: two tangent arcs with equal tangent lengths) that rounds the corner between
//! two lines with unit directions `in` and `out` from corner_m − t_in_m·in to corner_m + t_out_m·out,
//! when it stays within tolerance_m of both lines: each piece is checked at 9 points, plus where it
//! crosses the corner's bisector (the distance's ridge), with a bound on how much the distance can
//! rise between the checked points added. nullopt when it does not or no biarc exists.
//! A fillet touches both lines at the same distance from the corner; this one need not.
std::optional<std::array<PathSegment, 2>> corner_biarc(const Vec2& corner_m, const Vec2& in, const Vec2& out,
                                                       double t_in_m, double t_out_m, double tolerance_m) noexcept;

//! A path stage that replaces each blendable corner by a fillet arc: between two lines, when the
//! first is in blend mode (G64) with a positive tolerance, the turn exceeds `corner_angle_rad`,
//! and both lines have the same laser state and rapid flag (a mark must start where programmed).
//! Each line gives up at most half its programmed length to each of its two corners; what the two
//! blends leave of it, when shorter than a tenth of the tolerance, joins the following fillet
//! (arc_absorbing_line with a kink of at most a quarter of corner_angle_rad), so that chord-flattened
//! curves become chains of arcs without short lines between them (a curvature step each). The fillet
//! carries the first line's attributes with the lower of both feeds. Where the corner before was
//! blended too (and took at least a quarter of the first line), this fillet is bounded by half the
//! shorter line, not by the tolerance, and it would leave more of the first line than an absorbing
//! arc may take (the lines differ in length), the corner gets a corner_biarc instead, from where the
//! corner before left the first line to the second line's midpoint, if it keeps within P: then no
//! piece of line stays between the blends of a chord-flattened curve with uneven chords, and the
//! curvature steps from one corner's arcs to the next instead of to zero and back. Holds at most
//! two segments.
//! With `fit_chords` (ChordFitting::all) a ChordFitter in front first turns chains of short chords into
//! tangent biarcs within P, so only the vertices it leaves as corners get fillets; with
//! ChordFitting::merged it does so for chains of merged lines only.
//! The fillet's tolerance is the lower of both lines' (a merged line's is lowered by its merge, see
//! LineMerger). With a CornerSpeedModel (the planner's limits), each fillet between two lines is
//! chosen by choose_corner: the trim among d_max·2⁻ᵏ that loses least time, or no fillet where even
//! the best loses more than the corner without one (then passed at its velocity-step speed, about a
//! stop), so that a blend is never slower than the stop it replaces. The speed the first line can
//! have at the corner is bounded by its cap and by what it reaches over its length from the speed
//! bound at its start (the previous corner's pass speed). Without a model every fillet takes the
//! whole tolerance.
class CornerBlender final : public PathSource {
 public:
  CornerBlender(PathSource& source, double corner_angle_rad, bool fit_chords = false);
  CornerBlender(PathSource& source, double corner_angle_rad, ChordFitting fitting, const CornerSpeedModel& model);
  std::optional<PathSegment> next() override;

 private:
  //! The fillet choose_corner picks for the corner between held_ and `b` (nullopt: none), and the
  //! speed bound it leaves at b's start.
  std::optional<CornerFillet> chosen_fillet(const CornerFillet& full, const PathSegment& b, const Vec2& in,
                                            const Vec2& out, double tolerance_m, double max_trim_m);
  //! The bound on the speed at held_'s start: the corner before, and the arc that ends there (its
  //! cap, and the curvature step into held_, v²/r ≤ j·τ).
  [[nodiscard]] double speed_bound_at_held_start() const noexcept;

  std::unique_ptr<ChordFitter> fitter_;  // null without fitting
  PathSource& source_;                   // the fitter, or the stage before
  double corner_angle_rad_;
  double corner_chord_;                // 2·sin(corner_angle_rad/2): |out − in| of a turn by that angle
  std::optional<PathSegment> held_;    // the last segment, whose end may still be trimmed
  double held_length_m_ = 0.0;         // its programmed length
  bool held_blended_ = false;          // its start was moved by the corner before
  std::optional<CornerSpeedModel> model_;
  double held_start_speed_m_s_ = 0.0;  // a bound on the speed at held_'s start (+inf: unknown)
  double next_start_speed_m_s_ = 0.0;  // the same for the segment after the corner being decided
  // The arc that ends at held_'s start (radius 0: none): it bounds that speed too, worked out only
  // when a corner is decided (speed_bound_at_held_start).
  double held_start_arc_radius_m_ = 0.0, next_start_arc_radius_m_ = 0.0;
  double held_start_arc_feed_m_s_ = 0.0, next_start_arc_feed_m_s_ = 0.0;
  std::deque<PathSegment> ready_;
  bool exhausted_ = false;
};

}  // namespace stiffpath::motion
