// Which rounding of a G64 corner is fastest, a stop included: a blend must never lose to the stop it replaces.
#pragma once

#include "stiffpath/motion/limits.hpp"

namespace stiffpath::motion {

//! The machine's side of a corner decision: its limits and the junction time τ (JunctionRules).
struct CornerSpeedModel {
  MotionLimits limits;
  double junction_time_s = 0.5e-3;
};

//! The geometry of a corner between two lines and the speeds around it.
struct CornerInput {
  double turn_rad = 0.0;          //!< φ, the turn angle (0 … π)
  double max_trim_m = 0.0;        //!< the trim of the fillet at the program's tolerance (within the lines' room)
  double in_speed_m_s = 0.0;      //!< the highest speed the path can have on the first line at the corner
  double out_speed_m_s = 0.0;     //!< the second line's speed cap
  double feed_m_s = 0.0;          //!< the fillet's feed: the lower of both lines'
};

//! What the corner becomes: a fillet with this trim, or (trim 0) none, the corner then passed at the
//! speed of its velocity step, j·τ²/(2·sin(φ/2)) (junction.hpp; 1.7 mm/s for 90° at 5 g / 5 ms):
//! about a stop, never slower than one.
struct CornerChoice {
  double trim_m = 0.0;
  double pass_speed_m_s = 0.0;  //!< the fillet's speed through the corner in the model (0 without fillet)
  double loss_s = 0.0;          //!< time lost against cruising on, the chosen way (model)
  double stop_loss_s = 0.0;     //!< the same without a fillet (0 when the full fillet needs no slowing down)
};

//! The time a corner costs against cruising through it, as a stop or as a fillet of trim d (radius
//! r = d / tan(φ/2), arc length r·φ, replacing 2d of line): the first line slows from its speed u_in
//! to the pass speed w (speed_change: jerk-limited, zero acceleration at both ends), the arc is
//! planned from w to w under its own limits (segment_limits: the centripetal share of a and j), and the
//! second line speeds up from w to u_out. w is the lowest of both speeds, the arc's cap and the
//! junction rule for the curvature step between line and arc, w²/r ≤ j·τ. Loss of a speed change
//! from u to w over distance D: T − D/u.
//!
//! A blend is chosen only where its loss is at most that of the corner without fillet (which is at
//! most a stop's), so that it is never slower than stopping (the arc at w is a plan the planner can follow, so the planner's time is at most the
//! model's; and for lower approach speeds than u_in the blend only gains on the stop). Among trims
//! d_max·2⁻ᵏ (k = 0 … 10) the one with the least loss is taken: a smaller fillet is passed slower but
//! is shorter. Where the full fillet already passes at min(u_in, u_out), it is taken at once.
CornerChoice choose_corner(const CornerInput& corner, const CornerSpeedModel& model) noexcept;

}  // namespace stiffpath::motion
