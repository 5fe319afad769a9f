/* stiffpathkins: LinuxCNC kinematics of a stiffpath five-bar; the math comes from the stiffpath library.
 *
 * Joints 0 and 1 are the actuated angles θ1, θ2 in degrees; axes X and Y are the end point in
 * machine units (module parameter `units`). Forward and inverse kinematics are the library's
 * (stiffpath_forward / stiffpath_inverse of include/stiffpath/stiffpath.h) for the robot named by the
 * INI's [STIFFPATH]ROBOT (a preset: oc-gu, oc-gl, sc-gu, sc-gl, or a robot file), so whatever geometry the
 * robot file describes, this module follows it, and the INI names the robot once:
 *   [KINS]KINEMATICS = stiffpathkins          (HAL: loadrt [KINS]KINEMATICS)
 *   [STIFFPATH]ROBOT = /path/to/robot.json
 * The module parameters `robot` and `units` override the INI ([STIFFPATH]ROBOT, [TRAJ]LINEAR_UNITS); under
 * halrun, which sets no INI_FILE_NAME, `robot` must be given.
 * The inverse refuses (returns −1, which stops motion) a point outside the robot's singularity
 * margin; read-only parameters show the robot file's joint limits in degrees, to compare with the
 * INI's [JOINT_n] limits. See docs/linuxcnc.md. */
#include "hal.h"
#include "kinematics.h"
#include "rtapi.h"
#include "rtapi_app.h"
#include "rtapi_math.h"
#include "rtapi_string.h"
#include "stiffpath/stiffpath.h"
#include "stiffpath_ini.h"

MODULE_AUTHOR("stiffpath");
MODULE_DESCRIPTION("Five-bar kinematics from the stiffpath library");
MODULE_LICENSE("GPL");

static char *robot = "";
RTAPI_MP_STRING(robot, "stiffpath robot: a preset name or the absolute path of a robot file (default: the INI's [STIFFPATH]ROBOT)");
static char *units = "";
RTAPI_MP_STRING(units, "machine linear units: mm, inch or m (default: the INI's [TRAJ]LINEAR_UNITS, else mm)");

KINS_NOT_SWITCHABLE
EXPORT_SYMBOL(kinematicsType);
EXPORT_SYMBOL(kinematicsForward);
EXPORT_SYMBOL(kinematicsInverse);

#define DEG_PER_RAD (180.0 / M_PI)

static int comp_id = -1;
static stiffpath_robot *the_robot = NULL;
static double m_per_unit = 0.001;

static struct hal_data {
  hal_u32_t *inverse_failures; /* pin out: how many inverse calls were refused */
  hal_s32_t *last_status;      /* pin out: stiffpath_status of the last refused call */
  hal_float_t min_deg[2];      /* read-only params: the robot's joint limits */
  hal_float_t max_deg[2];
  hal_float_t max_velocity_deg_s[2];
  hal_float_t max_acceleration_deg_s2[2];
} *data = NULL;

KINEMATICS_TYPE kinematicsType(void) { return KINEMATICS_BOTH; }

int kinematicsForward(const double *joints, EmcPose *pos, const KINEMATICS_FORWARD_FLAGS *fflags,
                      KINEMATICS_INVERSE_FLAGS *iflags) {
  (void)fflags;
  (void)iflags;
  const double q_rad[2] = {joints[0] / DEG_PER_RAD, joints[1] / DEG_PER_RAD};
  double p_m[2];
  const int status = stiffpath_forward(the_robot, q_rad, p_m);
  if (status != STIFFPATH_OK) {
    *data->last_status = status;
    return -1;
  }
  pos->tran.x = p_m[0] / m_per_unit;
  pos->tran.y = p_m[1] / m_per_unit;
  pos->tran.z = 0.0;
  pos->a = pos->b = pos->c = 0.0;
  pos->u = pos->v = pos->w = 0.0;
  return 0;
}

int kinematicsInverse(const EmcPose *pos, double *joints, const KINEMATICS_INVERSE_FLAGS *iflags,
                      KINEMATICS_FORWARD_FLAGS *fflags) {
  (void)iflags;
  (void)fflags;
  const double p_m[2] = {pos->tran.x * m_per_unit, pos->tran.y * m_per_unit};
  double q_rad[2];
  const int status = stiffpath_inverse(the_robot, p_m, q_rad);
  if (status != STIFFPATH_OK) {
    *data->inverse_failures += 1;
    *data->last_status = status;
    return -1;
  }
  joints[0] = q_rad[0] * DEG_PER_RAD;
  joints[1] = q_rad[1] * DEG_PER_RAD;
  return 0;
}

/* LinuxCNC's names of [TRAJ]LINEAR_UNITS and ours. */
static int parse_units(const char *text, double *meters) {
  if (strcmp(text, "mm") == 0 || strcmp(text, "metric") == 0) *meters = 0.001;
  else if (strcmp(text, "inch") == 0 || strcmp(text, "in") == 0 || strcmp(text, "imperial") == 0) *meters = 0.0254;
  else if (strcmp(text, "m") == 0) *meters = 1.0;
  else return -1;
  return 0;
}

/* The robot and units: the module parameters, else the INI's [STIFFPATH]ROBOT and [TRAJ]LINEAR_UNITS. */
static int find_settings(char *robot_name, size_t robot_size, char *unit_name, size_t unit_size) {
  const char *why = "";
  if (robot[0]) {
    snprintf(robot_name, robot_size, "%s", robot);
  } else if (stiffpath_ini_setting("ROBOT", robot_name, robot_size, &why) != 0) {
    rtapi_print_msg(RTAPI_MSG_ERR, "stiffpathkins: no robot: give robot=... or [STIFFPATH]ROBOT in the INI file (%s)\n",
                    why);
    return -1;
  }
  const char *ini = getenv("INI_FILE_NAME");
  if (units[0]) snprintf(unit_name, unit_size, "%s", units);
  else if (!ini || stiffpath_ini_get(ini, "TRAJ", "LINEAR_UNITS", unit_name, unit_size) != 0) snprintf(unit_name, unit_size, "mm");
  return 0;
}

static int export_pins(void) {
  stiffpath_robot_info info;
  if (stiffpath_robot_get_info(the_robot, &info) != STIFFPATH_OK) return -1;
  data = hal_malloc(sizeof *data);
  if (!data) return -1;
  int r = 0;
  r |= hal_pin_u32_newf(HAL_OUT, &data->inverse_failures, comp_id, "stiffpathkins.inverse-failures");
  r |= hal_pin_s32_newf(HAL_OUT, &data->last_status, comp_id, "stiffpathkins.last-status");
  for (int j = 0; j < 2 && r == 0; ++j) {
    r |= hal_param_float_newf(HAL_RO, &data->min_deg[j], comp_id, "stiffpathkins.joint.%d.min-deg", j);
    r |= hal_param_float_newf(HAL_RO, &data->max_deg[j], comp_id, "stiffpathkins.joint.%d.max-deg", j);
    r |= hal_param_float_newf(HAL_RO, &data->max_velocity_deg_s[j], comp_id, "stiffpathkins.joint.%d.max-velocity-deg-s",
                              j);
    r |= hal_param_float_newf(HAL_RO, &data->max_acceleration_deg_s2[j], comp_id,
                              "stiffpathkins.joint.%d.max-acceleration-deg-s2", j);
    data->min_deg[j] = info.joints[j].min_rad * DEG_PER_RAD;
    data->max_deg[j] = info.joints[j].max_rad * DEG_PER_RAD;
    data->max_velocity_deg_s[j] = info.joints[j].max_velocity_rad_s * DEG_PER_RAD;
    data->max_acceleration_deg_s2[j] = info.joints[j].max_acceleration_rad_s2 * DEG_PER_RAD;
  }
  if (r) return r;
  *data->inverse_failures = 0;
  *data->last_status = STIFFPATH_OK;
  return 0;
}

int rtapi_app_main(void) {
  char error[512], robot_name[1024], unit_name[64];
  if (find_settings(robot_name, sizeof robot_name, unit_name, sizeof unit_name) != 0) return -EINVAL;
  if (parse_units(unit_name, &m_per_unit) != 0) {
    rtapi_print_msg(RTAPI_MSG_ERR, "stiffpathkins: units %s: must be mm (metric), inch (imperial) or m\n", unit_name);
    return -EINVAL;
  }
  the_robot = stiffpath_robot_load(robot_name, error, sizeof error);
  if (!the_robot) {
    rtapi_print_msg(RTAPI_MSG_ERR, "stiffpathkins: robot %s: %s\n", robot_name, error);
    return -EINVAL;
  }
  comp_id = hal_init("stiffpathkins");
  if (comp_id < 0) {
    stiffpath_robot_free(the_robot);
    the_robot = NULL;
    return comp_id;
  }
  if (export_pins() != 0) {
    rtapi_print_msg(RTAPI_MSG_ERR, "stiffpathkins: cannot create its pins and parameters\n");
    hal_exit(comp_id);
    stiffpath_robot_free(the_robot);
    the_robot = NULL;
    return -ENOMEM;
  }
  hal_ready(comp_id);
  return 0;
}

void rtapi_app_exit(void) {
  hal_exit(comp_id);
  stiffpath_robot_free(the_robot);
  the_robot = NULL;
}
