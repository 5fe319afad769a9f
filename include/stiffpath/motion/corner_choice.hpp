// Which rounding of a G64 corner is fastest, a stop included: a blend must never lose to the stop it replaces.
#pragma once

#include "stiffpath/motion/limits.hpp"

namespace stiffpath::motion {

//! The machine's side of a corner decision: its limits and the junction time τ (JunctionRules).
struct CornerSpeedModel {
  MotionLimits limits;
  double junction_time_s = 0.5e-3;
};

//! A corner between two lines and what bounds the speed around it.
struct CornerInput {
  double turn_rad = 0.0;            //!< φ, the turn angle (0 … π)
  double max_trim_m = 0.0;          //!< the trim of the fillet at the program's tolerance (within the lines' room)
  double in_length_m = 0.0;         //!< the first line, from its start to the corner
  double out_length_m = 0.0;        //!< the second line, from the corner to its end
  double in_start_speed_m_s = 0.0;  //!< a bound on the speed at the first line's start (+inf: none known)
  double in_cap_m_s = 0.0;          //!< the first line's speed cap, min(F, v_max)
  double out_cap_m_s = 0.0;         //!< the second line's
  double feed_m_s = 0.0;            //!< the fillet's feed: the lower of both lines'
};

//! What the corner becomes: a fillet with this trim, or (trim 0) none, the corner then passed at the
//! speed of its velocity step, j·τ²/(2·sin(φ/2)) (junction.hpp; 1.7 mm/s for 90° at 5 g / 5 ms):
//! about a stop, never slower than one.
struct CornerChoice {
  double trim_m = 0.0;
  double pass_speed_m_s = 0.0;  //!< the speed through the corner in the model
  double time_s = 0.0;          //!< the model's time from the first line's start to the second's end
  double unrounded_time_s = 0.0;  //!< the same without a fillet (0 when the full fillet is taken at once)
};

//! The time from the first line's start to the second line's end, as the fastest jerk-limited motion
//! (speed_change, solve_profile) that starts within the bound at the first line's start and passes the
//! corner at w: the first line, shortened by the trim d, slows to w at its end; a fillet of trim d
//! (radius r = d / tan(φ/2), arc length r·φ) is planned from w to w under its own limits
//! (segment_limits); the second line speeds up from w as far as it can (its end is free). w is the
//! lowest of both caps, the arc's cap, the junction rule for the curvature step between line and arc
//! (w²/r ≤ j·τ) and what the first line can reach; without a fillet w is the velocity-step speed.
//!
//! A fillet is chosen only where its time is at most that of the corner without one (whose speed is
//! at least a stop's), so that a blend is never slower than stopping: the model's motion is one the
//! planner can follow, so the planner's time is at most the model's. Among trims d_max·2⁻ᵏ (k = 0 …
//! 10, until the time rises again from k = 2 on) the fastest is taken: a smaller fillet is passed
//! slower but is shorter. Where the full fillet already passes at the lower of both caps, it is taken
//! at once.
CornerChoice choose_corner(const CornerInput& corner, const CornerSpeedModel& model) noexcept;

}  // namespace stiffpath::motion
