// stiffpathlaser: a laser's enable and power from LinuxCNC's M3/M4/M5, S and M62/M63, in time with the joint commands.
component stiffpathlaser "Laser enable and power from M3/M4/M5, S and M62/M63, delayed to the joint commands (stiffpath)";

description """
Turns what LinuxCNC's interpreter says about the laser into a digital enable and a power (0..1, for
a PWM generator or an analog output), with stiffpath's G-code semantics (docs/motion.md):

- M3 or M4 (*on*, from spindle.0.on) with S (*s*, spindle.0.speed-out-abs): power min(S, s-max) / s-max;
- M4 (*dynamic*, spindle.0.reverse): that power times min(1, current-vel / requested-vel), so that
  every millimetre gets the energy it gets at the programmed feed;
- M62/M63 (*full*, motion.digital-out-NN, switched by motion in step with the path): full power;
- the laser fires only while the tool moves (*current-vel* > 0) and not on a rapid (*motion-type* 1):
  LinuxCNC executes M3/M5 only once the motion before them has stopped, and the laser must not burn
  while the robot stands there. current-vel rises in the period whose Cartesian command first leaves
  the point and falls in the one that reaches the end; motion-type (and M62's output) change with the
  segment, motion-type a period late, so a period's move is read from the motion-type of the period
  after. A pause of at most *delay* periods inside a cut (an exact-stop corner rests one period) keeps
  the laser on.

Motion's joint command in period k is the cubic B-spline (q[k-3] + 4 q[k-2] + q[k-1]) / 6 of the
kinematics' knots, centred two periods behind motion's Cartesian command, and stiffpathcomp's
correction is aligned with it (docs/linuxcnc.md). So the enable and the power go out *delay* periods
(default 2) after motion set them: the laser switches with the joint command that takes the robot to
the point where the program switches it. *gate* (e.g. machine on and no stiffpathcomp fault) acts at
once, without the delay. Add the function after motion-controller.
""";

pin in bit on "laser on at S: spindle.0.on (M3, M4)";
pin in bit dynamic "power scaled by the speed: spindle.0.reverse (M4)";
pin in bit full "laser on at full power: motion.digital-out-NN (M62/M63)";
pin in float s "S: spindle.0.speed-out-abs";
pin in s32 motion_type "motion.motion-type: no fire on rapids (1)";
pin in float current_vel "motion.current-vel, machine units per second";
pin in float requested_vel "motion.requested-vel, machine units per second";
pin in bit gate = 1 "the laser may fire (machine on, no fault); acts without delay";
pin out bit laser "the laser's digital enable, delay periods after motion";
pin out float power "laser power 0..1 (0 while the enable is off), delay periods after motion";
param rw float s_max = 1000 "S of full power (GRBL's $30; `stiffpath run --s-max`)";
param rw u32 delay = 2 "servo periods from motion's output to the joint command that realises it (at most 15)";

option singleton yes;
function _ fp "after motion-controller";
license "GPL";
author "stiffpath";
;;
#define STIFFPATHLASER_HISTORY 16

static double power_history[STIFFPATHLASER_HISTORY]; /* power the program asked for in the last periods */
static int moving_history[STIFFPATHLASER_HISTORY];   /* whether the tool moved in them */
static int type_history[STIFFPATHLASER_HISTORY];     /* motion-type in them */
static unsigned next_slot = 0;
static int fired_last = 0;                            /* the laser fired in the period put out last */

/* The power the program asks for now, whatever the motion: the laser on with a positive power, else 0. */
static double requested_power(struct __comp_state *__comp_inst) {
  double p = 0.0;
  if (full) {
    p = 1.0;
  } else if (on) {
    p = (s_max > 0.0 && s > 0.0) ? s / s_max : 0.0;
    if (p > 1.0) p = 1.0;
    if (dynamic) {
      const double ratio = requested_vel > 0.0 ? current_vel / requested_vel : 0.0;
      p *= ratio < 0.0 ? 0.0 : (ratio > 1.0 ? 1.0 : ratio);
    }
  }
  return p > 0.0 ? p : 0.0; /* NaN too */
}

/* The power period `slot` cuts with, `newest` being the latest period known: motion-type lags the
 * Cartesian command by a period, so the period after tells which move a period belongs to. */
static double cutting_power(unsigned slot, unsigned newest) {
  const unsigned type_slot = slot == newest ? slot : (slot + 1) % STIFFPATHLASER_HISTORY;
  return type_history[type_slot] == 1 ? 0.0 : power_history[slot];
}

FUNCTION(_) {
  (void)period;
  const unsigned d = delay < STIFFPATHLASER_HISTORY ? delay : STIFFPATHLASER_HISTORY - 1;
  const unsigned newest = next_slot;
  power_history[newest] = requested_power(__comp_inst);
  moving_history[newest] = current_vel > 0.0;
  type_history[newest] = motion_type;
  /* The period put out now is d periods old; the d periods after it are already known. It fires if the
   * tool moves in it with the laser asked for, or if it is a pause within a cut: the period before fired
   * and the tool moves on with the laser within the known periods (an exact-stop corner, one period at rest). */
  const unsigned out = (newest + STIFFPATHLASER_HISTORY - d) % STIFFPATHLASER_HISTORY;
  const double p = cutting_power(out, newest);
  int fire = p > 0.0 && moving_history[out];
  for (unsigned i = 1; !fire && fired_last && p > 0.0 && i <= d; ++i) {
    const unsigned later = (out + i) % STIFFPATHLASER_HISTORY;
    fire = cutting_power(later, newest) > 0.0 && moving_history[later];
  }
  next_slot = (newest + 1) % STIFFPATHLASER_HISTORY;
  fired_last = fire;
  laser = gate && fire;
  power = laser ? p : 0.0;
}
