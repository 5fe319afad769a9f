// How fast the path may pass the junction between two segments (corners, tangent joins, curvature steps).
#pragma once

#include <cstdint>

#include "stiffpath/motion/limits.hpp"
#include "stiffpath/motion/path_segment.hpp"
#include "stiffpath/motion/segment_limits.hpp"

namespace stiffpath::motion {

//! The rules at junctions. Every profile starts and ends with zero tangential acceleration, so a
//! junction passed at speed v only steps the velocity by 2·v·sin(φ/2) (φ: turn angle) and the
//! acceleration by v²·|κ₂N₂ − κ₁N₁| (the centripetal terms). Both steps are bounded by what the jerk
//! limit allows over one junction time τ: |Δv| ≤ j·τ², |Δa| ≤ j·τ. With τ = one 2 kHz sample, the
//! sampled trajectory cannot tell such a step from a jerk-limited ramp.
struct JunctionRules {
  double junction_time_s = 0.5e-3;  //!< τ (s); 0.5 ms = one period of the 2 kHz loop (fig. 4.3)
  //! A junction turning by more than this is a corner (rad): G61 stops there and G64 rounds it
  //! (between lines). 1 mrad also tolerates the kinks of coordinates rounded to 1 µm on 1 mm moves.
  double corner_angle_rad = 1e-3;
  //! G64: true, chains of short chords (CAM's flattened curves) are refitted as tangent biarcs
  //! within P before the remaining corners get fillets (ChordFitter; `--chords fit`); false (the
  //! default), every vertex gets a fillet or corner biarc. Fitting about doubles the segments; measured,
  //! it shortens most finely flattened smooth curves (random rosettes: 23 of 40, by up to 32 %) but
  //! lengthens coarse ones (the gear outline's contour by 6.9 %) and 0.1 mm-chord circles by 0.1-3.1 %
  //! (docs/motion.md, "Fitted chords").
  bool fit_chords = false;
  //! G64: true (the default, `--chords auto`), chains of lines merged by LineMerger (staircases, which
  //! become uneven chords of a smooth curve) are fitted even when fit_chords is false: their blends
  //! would step in curvature at every chord (measured in docs/motion.md).
  bool fit_merged_chords = true;
};

//! What bounds the path's speed at a junction or on a segment: the account of a plan's lost time
//! (SlowdownReport) names these.
enum class SpeedLimit : std::uint8_t {
  none,            //!< nothing but the feed and the machine's speed limit
  rest,            //!< the program's start and end, at rest
  dwell,           //!< a dwell (G4, G4 P0), a program stop (M0/M1): the path stops there
  exact_stop,      //!< a corner in exact-stop mode (G61)
  corner,          //!< a sharp corner not rounded (G0 to G1, a laser switch, or where no fillet pays): 2·v·sin(φ/2) ≤ j·τ²
  curvature_step,  //!< a step of curvature (a line into an arc, between a blend's arcs): v²·Δκ ≤ j·τ
  arc_speed,       //!< an arc's speed cap: its centripetal share of the acceleration and jerk limits
  feed,            //!< a lower programmed feed next to it
};

//! A short stable name ("curvature_step", …): the JSON key.
const char* to_string(SpeedLimit limit) noexcept;
//! A phrase for the summaries ("curvature steps (v^2*dk <= j*tau)", …).
const char* describe(SpeedLimit limit) noexcept;

//! The turn angle φ ∈ [0, π] between two unit tangents.
double turn_angle_rad(const Vec2& from, const Vec2& to) noexcept;

//! The highest speed at the junction from `before` into `after`: 0 next to a dwell and at corners
//! in exact-stop mode (G61, the mode of `before`); otherwise the lower of both segments' caps and
//! the two step bounds above. `cause`, when given, receives the rule that gives the bound (a cap:
//! arc_speed when it is an arc's below its feed, else feed).
double junction_speed_limit(const PathSegment& before, const SegmentLimits& before_limits, const PathSegment& after,
                            const SegmentLimits& after_limits, const MotionLimits& limits,
                            const JunctionRules& rules, SpeedLimit* cause = nullptr) noexcept;

//! The highest speed at which a tangent junction (turn ≤ corner_angle_rad) may be passed with a
//! tangential acceleration of up to `tangential_acceleration_m_s2` across it, i.e. inside a run of
//! segments planned as one profile: then the acceleration also steps by a_t·2·sin(φ/2), which
//! takes its share of the bound j·τ before the centripetal step v²·|κ₂N₂ − κ₁N₁| gets the rest.
//! 0 when the junction is not tangent, borders a dwell, or a_t alone would use up the bound.
double tangent_junction_speed_limit(const PathSegment& before, const SegmentLimits& before_limits,
                                    const PathSegment& after, const SegmentLimits& after_limits,
                                    const MotionLimits& limits, const JunctionRules& rules,
                                    double tangential_acceleration_m_s2) noexcept;

}  // namespace stiffpath::motion
