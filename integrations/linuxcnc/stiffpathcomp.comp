// stiffpathcomp: corrects a five-bar's joint commands for its predicted elastic deflection, each servo period.
component stiffpathcomp "Stiffness compensation of a five-bar robot's joint commands (stiffpath)";

description """
Runs stiffpath's real-time compensation step (thesis fig. 4.3) inside the servo thread. Add it
*after* motion-controller. LinuxCNC turns each Cartesian command c[i] (axis.x.pos-cmd,
axis.y.pos-cmd) into joint angles q[i] = IK(c[i]) and passes them through its cubic interpolator, a
uniform cubic B-spline: the joint command of period k is

  joint.N.pos-cmd[k] = (q[k-3] + 4 q[k-2] + q[k-1]) / 6,

two periods behind the Cartesian command. So when period k's joint command goes out, c[k] is
already known, and the acceleration of c[k-1] comes from a centred second difference:

  v = (c[k] - c[k-2]) / 2T,  a = (c[k] - 2 c[k-1] + c[k-2]) / T²,
  j = (c[k] - 3 c[k-1] + 3 c[k-2] - c[k-3]) / T³  (backward, centred at k-1.5).

The step turns a into the D'Alembert force F = -m a, the predicted deflection Δ = C(p) F and the
corrected joint angles IK(c - Δ), checking reach and joint limits; with the blend factor b,
d[k-1] = IK(c[k-1] - b Δ) - IK(c[k-1]) is the joint correction.
The component adds (d[k-3] + 4 d[k-2] + d[k-1]) / 6 to the motor command and subtracts it from the
motor feedback: the drive gets the B-spline of the corrected joint angles, exactly what LinuxCNC
would send if its kinematics returned IK(c - Δ), and motion sees its own path.

b is the blend factor: it follows enable × gain, changing by at most T / ramp-time per period, and
starts moving five periods after enable rises (the command jumps when the machine is homed; the
jump must leave the difference stencil first). Δ does not depend on the gain, so IK(c - bΔ) is what
the library computes at gain b; the limits are checked at gain 1.

If the step refuses (unreachable corrected target, a joint limit, a non-finite input), the
component holds the last good command, raises *fault* and keeps holding until *reset* rises: wire
*fault* into the E-stop chain. After the reset it starts afresh: the blend factor ramps in again
from 0 five periods after the reset. See docs/linuxcnc.md.
""";

pin in float x_cmd "Cartesian X command, machine units (axis.x.pos-cmd)";
pin in float y_cmd "Cartesian Y command, machine units (axis.y.pos-cmd)";
pin in float joint.#.cmd_in[2] "motion's motor command, degrees (joint.N.motor-pos-cmd)";
pin out float joint.#.cmd_out[2] "corrected motor command to the drive, degrees";
pin in float joint.#.fb_in[2] "the drive's position feedback, degrees";
pin out float joint.#.fb_out[2] "feedback for motion with the correction taken out (joint.N.motor-pos-fb)";
pin in float joint.#.pos_cmd[2] "optional: motion's joint.N.pos-cmd, only for the lag-error check";
pin out float joint.#.correction_deg[2] "correction added to the command this period";
pin in bit enable "compensate (typically: all joints homed)";
pin in float gain = 1.0 "gain k, used within 0..1";
pin in bit reset "a rising edge clears fault";
pin out bit active "the correction is being applied (blend factor > 0, no fault)";
pin out bit fault "a step was refused: the command is held";
pin out s32 status "stiffpath_status of the last step (0 = ok)";
pin out u32 refusals "refused steps since load";
pin out float blend "the blend factor b";
pin out float deflection_x_um "predicted deflection Δx at c[k-1]";
pin out float deflection_y_um "predicted deflection Δy";
pin out float acceleration_x_m_s2 "centred second difference of the Cartesian command";
pin out float acceleration_y_m_s2;
pin out float joint.#.load_torque_nm[2] "torque feed-forward for a drive that takes one: (tau[k-3] + 4 tau[k-2] + tau[k-1]) / 6 with tau = J^T m a of c, N m at the joint (divide by the gear ratio for the motor); 0 while not active";
pin out float lag_error_deg "max over the joints of |joint.N.pos-cmd - (q[k-3] + 4 q[k-2] + q[k-1]) / 6|: 0 when motion interpolates as assumed";
param rw float m_per_unit = 0.001 "metres per machine unit (0.001 for mm)";
param rw float ramp_time = 0.1 "seconds for the blend factor to go from 0 to 1";

option singleton yes;
option extra_setup yes;
option extra_cleanup yes;
function _ fp "compensate; add to the servo thread after motion-controller";
license "GPL";
author "stiffpath";
include <rtapi_math.h>;
include <stiffpath/stiffpath.h>;
include "stiffpath_ini.h";
;;
static char *robot = "";
RTAPI_MP_STRING(robot, "stiffpath robot: a preset name or the absolute path of a robot file (default: the INI's [STIFFPATH]ROBOT)");
static char *model = "";
RTAPI_MP_STRING(model, "compliance model: a model file or built-in name (default: the INI's [STIFFPATH]MODEL when robot "
                       "comes from the INI, else the robot's own)");

#define DEG_PER_RAD (180.0 / M_PI)

static stiffpath_compensator *compensator = NULL;
static const stiffpath_robot *kinematics = NULL;
static double c_m[4][2];         /* Cartesian commands c[k], c[k-1], c[k-2], c[k-3] */
static double q_deg[3][2];       /* uncorrected IK(c[k-1]), IK(c[k-2]), IK(c[k-3]) */
static double d_deg[3][2];       /* blended joint corrections d[k-1], d[k-2], d[k-3] */
static double tau_Nm[3][2];      /* load torques J^T m a at c[k-1], c[k-2], c[k-3] */
static int primed = 0;
static int enabled_periods = 0;
static int q_known = 0;          /* how many of q_deg's rows hold computed values */
static hal_bit_t last_reset = 0;
static double held_out[2], held_correction[2];

EXTRA_SETUP() {
  static char robot_name[1024], model_name[1024]; /* called once, at load time: not on the stack */
  char error[512];
  const char *why = "";
  (void)prefix;
  (void)extra_arg;
  snprintf(robot_name, sizeof robot_name, "%s", robot);
  snprintf(model_name, sizeof model_name, "%s", model);
  if (!robot[0]) { /* both from the INI: [STIFFPATH]ROBOT, and MODEL if it has one */
    if (stiffpath_ini_setting("ROBOT", robot_name, sizeof robot_name, &why) != 0) {
      rtapi_print_msg(RTAPI_MSG_ERR, "stiffpathcomp: no robot: give robot=... or [STIFFPATH]ROBOT in the INI file (%s)\n", why);
      return -EINVAL;
    }
    if (!model[0] && stiffpath_ini_setting("MODEL", model_name, sizeof model_name, &why) != 0) model_name[0] = '\0';
  }
  compensator = stiffpath_compensator_create(robot_name, model_name[0] ? model_name : NULL, NULL, error, sizeof error);
  if (!compensator) {
    rtapi_print_msg(RTAPI_MSG_ERR, "stiffpathcomp: robot %s, model %s: %s\n", robot_name,
                    model_name[0] ? model_name : "(the robot's own)", error);
    return -EINVAL;
  }
  kinematics = stiffpath_compensator_robot(compensator);
  return 0;
}

EXTRA_CLEANUP() {
  stiffpath_compensator_free(compensator);
  compensator = NULL;
}

/* The blend factor's next value: towards the target (kept in [0, 1]), at most T / ramp-time per period. */
static double next_blend(double b, double target, double T, double ramp) {
  if (!(target >= 0.0)) target = 0.0;
  if (target > 1.0) target = 1.0;
  if (ramp <= 0.0) return target;
  const double step = T / ramp;
  if (target > b + step) return b + step;
  if (target < b - step) return b - step;
  return target;
}

static void shift(double (*rows)[2], int n) {
  for (int r = n - 1; r > 0; --r) {
    rows[r][0] = rows[r - 1][0];
    rows[r][1] = rows[r - 1][1];
  }
}

/* The B-spline weight of three consecutive knots, as motion's cubic interpolator applies it. */
static double spline(double newest, double middle, double oldest) { return (oldest + 4.0 * middle + newest) / 6.0; }

/* Hold the last good command; the feedback keeps the last correction taken out, so that motion
 * sees the drive stop and its following error grows. */
static void hold(struct __comp_state *__comp_inst) {
  for (int i = 0; i < 2; ++i) {
    joint_cmd_out(i) = held_out[i];
    joint_fb_out(i) = joint_fb_in(i) - held_correction[i];
  }
  active = 0;
}

/* A refused step: hold, and after the reset start afresh (blend 0, no past corrections). */
static void refuse(struct __comp_state *__comp_inst, int why) {
  status = why;
  fault = 1;
  refusals += 1;
  hold(__comp_inst);
  blend = 0.0;
  enabled_periods = 0;
  q_known = 0;
  for (int r = 0; r < 3; ++r) d_deg[r][0] = d_deg[r][1] = tau_Nm[r][0] = tau_Nm[r][1] = 0.0;
  for (int i = 0; i < 2; ++i) joint_load_torque_nm(i) = 0.0;
}

FUNCTION(_) {
  const double T = fperiod;
  shift(c_m, 4);
  c_m[0][0] = x_cmd * m_per_unit;
  c_m[0][1] = y_cmd * m_per_unit;
  if (!primed) { /* a machine at rest before the first period: nothing to difference */
    for (int r = 1; r < 4; ++r) {
      c_m[r][0] = c_m[0][0];
      c_m[r][1] = c_m[0][1];
    }
    primed = 1;
  }

  if (reset && !last_reset) fault = 0;
  last_reset = reset;
  if (fault) {
    hold(__comp_inst);
    return;
  }

  enabled_periods = enable ? (enabled_periods < 5 ? enabled_periods + 1 : 5) : 0;
  blend = next_blend(blend, enabled_periods == 5 ? gain : 0.0, T, ramp_time);
  shift(q_deg, 3);
  shift(d_deg, 3);
  d_deg[0][0] = d_deg[0][1] = 0.0;
  shift(tau_Nm, 3);
  tau_Nm[0][0] = tau_Nm[0][1] = 0.0;
  if (blend > 0.0) {
    stiffpath_task_sample s;
    s.t_s = 0.0;
    for (int i = 0; i < 2; ++i) {
      s.p_m[i] = c_m[1][i];
      s.v_m_s[i] = (c_m[0][i] - c_m[2][i]) / (2.0 * T);
      s.a_m_s2[i] = (c_m[0][i] - 2.0 * c_m[1][i] + c_m[2][i]) / (T * T);
      s.j_m_s3[i] = (c_m[0][i] - 3.0 * c_m[1][i] + 3.0 * c_m[2][i] - c_m[3][i]) / (T * T * T);
      s.s_m_s4[i] = 0.0;
    }
    stiffpath_joint_command out;
    double q0[2];
    int st = stiffpath_compensator_step(compensator, &s, &out);
    if (st == STIFFPATH_OK) st = stiffpath_inverse(kinematics, s.p_m, q0);
    if (st != STIFFPATH_OK) {
      refuse(__comp_inst, st);
      return;
    }
    status = STIFFPATH_OK;
    /* The gain k < 1: the same Δ (it does not depend on k), p_cmd = p − kΔ; k = 1: the step's own angles. */
    double q[2] = {out.q_rad[0], out.q_rad[1]};
    if (blend != 1.0) {
      const double target[2] = {s.p_m[0] - blend * out.deflection_m[0], s.p_m[1] - blend * out.deflection_m[1]};
      st = stiffpath_inverse(kinematics, target, q);
      if (st != STIFFPATH_OK) {
        refuse(__comp_inst, st);
        return;
      }
    }
    for (int i = 0; i < 2; ++i) {
      q_deg[0][i] = q0[i] * DEG_PER_RAD;
      d_deg[0][i] = (q[i] - q0[i]) * DEG_PER_RAD;
      tau_Nm[0][i] = out.load_torque_Nm[i];
    }
    deflection_x_um = out.deflection_m[0] * 1e6;
    deflection_y_um = out.deflection_m[1] * 1e6;
    acceleration_x_m_s2 = s.a_m_s2[0];
    acceleration_y_m_s2 = s.a_m_s2[1];
    q_known = q_known < 3 ? q_known + 1 : 3;
    lag_error_deg = q_known < 3 ? 0.0
                                : fmax(fabs(joint_pos_cmd(0) - spline(q_deg[0][0], q_deg[1][0], q_deg[2][0])),
                                       fabs(joint_pos_cmd(1) - spline(q_deg[0][1], q_deg[1][1], q_deg[2][1])));
  } else {
    status = STIFFPATH_OK;
    q_known = 0;
    deflection_x_um = deflection_y_um = 0.0;
    acceleration_x_m_s2 = acceleration_y_m_s2 = 0.0;
    lag_error_deg = 0.0;
  }
  active = blend > 0.0;
  for (int i = 0; i < 2; ++i) {
    const double correction = spline(d_deg[0][i], d_deg[1][i], d_deg[2][i]);
    joint_correction_deg(i) = correction;
    joint_load_torque_nm(i) = active ? spline(tau_Nm[0][i], tau_Nm[1][i], tau_Nm[2][i]) : 0.0;
    joint_cmd_out(i) = joint_cmd_in(i) + correction;
    joint_fb_out(i) = joint_fb_in(i) - correction;
    held_out[i] = joint_cmd_out(i);
    held_correction[i] = correction;
  }
}
