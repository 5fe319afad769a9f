/* stiffpath.h: the C interface to stiffpath's real-time compensation step and its robot's kinematics.
 *
 * What a controller's servo loop or a drive vendor's firmware calls. Everything is plain C (C99),
 * every function is safe to call from C++ (none throws), and nothing below allocates memory except
 * the two create/load functions. Link with -lstiffpath_c (CMake: stiffpath::stiffpath_c; pkg-config:
 * stiffpath_c). Units are SI (m, s, rad, N, kg); every field names its unit.
 *
 * Typical use (docs/c_api.md):
 *
 *   char error[512];
 *   stiffpath_compensator *c = stiffpath_compensator_create("oc-gu", NULL, NULL, error, sizeof error);
 *   if (!c) { fprintf(stderr, "%s\n", error); return 2; }
 *   ...                                   // every servo period, in the real-time thread:
 *   stiffpath_task_sample s = {t, {x, y}, {vx, vy}, {ax, ay}, {jx, jy}, {0, 0}};
 *   stiffpath_joint_command out;
 *   if (stiffpath_compensator_step(c, &s, &out) != STIFFPATH_OK) hold_and_stop(&out);
 *   else send(out.q_rad[0], out.q_rad[1]);
 *   ...
 *   stiffpath_compensator_free(c);
 *
 * Thread safety: a robot or compensator may be used by several threads at once (step, forward and
 * inverse only read it); create and free are not real-time and must not race with its use. */
#ifndef STIFFPATH_STIFFPATH_H
#define STIFFPATH_STIFFPATH_H

#include <stddef.h>

#if defined(__GNUC__)
#define STIFFPATH_C_API __attribute__((visibility("default")))
#else
#define STIFFPATH_C_API
#endif
/* Seen from C++, no function of this interface throws. */
#ifdef __cplusplus
#define STIFFPATH_NOEXCEPT noexcept
#else
#define STIFFPATH_NOEXCEPT
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** Version of this interface; changes when a struct below or a function's meaning changes. */
#define STIFFPATH_C_API_VERSION 2

/** Outcome of a call. Anything but STIFFPATH_OK from a step means: do not send this command. */
typedef enum stiffpath_status {
  STIFFPATH_OK = 0,
  STIFFPATH_NOT_FINITE = 1,          /**< a NaN or infinity in the input */
  STIFFPATH_OUTSIDE_GRID = 2,        /**< the model's outside policy is "error" and p is off its grid */
  STIFFPATH_UNREACHABLE = 3,         /**< the point fails the robot's singularity margin */
  STIFFPATH_JOINT_POSITION = 4,      /**< a joint angle outside the robot's range */
  STIFFPATH_JOINT_VELOCITY = 5,      /**< a joint speed above the robot's limit */
  STIFFPATH_JOINT_ACCELERATION = 6,  /**< a joint acceleration above the robot's limit */
  STIFFPATH_INVALID_ARGUMENT = 7,    /**< a NULL pointer where an object was needed */
  STIFFPATH_BAD_INPUT = 8,           /**< a job's robot, model, program or option was refused: see the error text */
  STIFFPATH_STOPPED = 9              /**< a job's sink asked it to stop */
} stiffpath_status;

/** What the compliance model does with a point outside its measured grid. */
typedef enum stiffpath_outside_policy {
  STIFFPATH_OUTSIDE_MODEL_DEFAULT = 0, /**< the library default: refuse a point more than 1 mm off the grid */
  STIFFPATH_OUTSIDE_CLAMP = 1,         /**< use the nearest point of the grid's rectangle */
  STIFFPATH_OUTSIDE_EXTRAPOLATE = 2,   /**< extend the model's formula */
  STIFFPATH_OUTSIDE_ERROR = 3          /**< refuse the sample (STIFFPATH_OUTSIDE_GRID) */
} stiffpath_outside_policy;

/** How the deflection is predicted (stiffpath_options.method). */
typedef enum stiffpath_method {
  STIFFPATH_METHOD_QUASI_STATIC = 0, /**< the thesis's static deflection Δ = C·F */
  STIFFPATH_METHOD_DYNAMIC = 1       /**< the tip model with its damping inverted (default; docs/compensation.md) */
} stiffpath_method;

/** A reference filter's shaper (stiffpath_job_options.shaper). */
typedef enum stiffpath_shaper {
  STIFFPATH_SHAPER_NONE = 0, /**< no shaper (default) */
  STIFFPATH_SHAPER_ZV = 1,   /**< ZV input shaper following the tip's frequency */
  STIFFPATH_SHAPER_ZVD = 2   /**< ZVD input shaper */
} stiffpath_shaper;

/** A robot description (geometry, mass, limits), loaded from a robot file or a preset. Opaque. */
typedef struct stiffpath_robot stiffpath_robot;
/** A robot with a compliance model: the real-time compensation step. Opaque. */
typedef struct stiffpath_compensator stiffpath_compensator;

/** Settings of a compensator; stiffpath_default_options() gives the documented defaults. */
typedef struct stiffpath_options {
  double gain;          /**< k in p_cmd = p − k·Δ, finite and >= 0 (default 1) */
  int enabled;          /**< 0: p_cmd = p, the "without compensation" command (default 1) */
  int check_limits;     /**< check reach and joint limits on every step (default 1) */
  int outside_policy;   /**< a stiffpath_outside_policy (default STIFFPATH_OUTSIDE_MODEL_DEFAULT) */
  int method;           /**< a stiffpath_method (default STIFFPATH_METHOD_DYNAMIC, as every surface; a zeroed
                             struct asks for STIFFPATH_METHOD_QUASI_STATIC: start from stiffpath_default_options()) */
  double damping_ratio; /**< ζ of the tip's modes for STIFFPATH_METHOD_DYNAMIC, 0..2; negative (the default, -1):
                             the robot file's tip_damping_ratio, 0.05 when it gives none */
} stiffpath_options;

/** One sample of the planned end-point trajectory (SI, the robot's base frame). */
typedef struct stiffpath_task_sample {
  double t_s;           /**< time; copied to the command */
  double p_m[2];        /**< position x, y */
  double v_m_s[2];      /**< velocity */
  double a_m_s2[2];     /**< acceleration: drives the D'Alembert force F = −m·a (thesis eq. 4.4) */
  double j_m_s3[2];     /**< jerk: enters the commanded joint velocity only */
  double s_m_s4[2];     /**< snap: enters the commanded joint acceleration only; 0 inside jerk-limited phases */
} stiffpath_task_sample;

/** The command for one sample. Joint values are meaningful only when status is STIFFPATH_OK; they
 *  are never NaN. Every field of a joint file (docs/compensation.md, "Output formats") is the member of the
 *  same name here, in SI: t_s, q_rad, qd_rad_s, qdd_rad_s2, laser, power, target_m, command_m, force_N, line. */
typedef struct stiffpath_joint_command {
  double t_s;
  double q_rad[2];          /**< θ1, θ2 = IK(p_cmd) */
  double qd_rad_s[2];       /**< ω1, ω2 */
  double qdd_rad_s2[2];     /**< α1, α2 */
  double target_m[2];       /**< the planned point p */
  double command_m[2];      /**< the corrected target p_cmd = p − k·Δ */
  double force_N[2];        /**< F = −m·a at the platform's centre of gravity */
  double deflection_m[2];   /**< predicted Δ = C(p)·F (thesis eqs. 4.6–4.7, 4.12) */
  double load_torque_Nm[2]; /**< τ = Jᵀ·m·a at the joints (J at p_cmd): the platform's inertial load on the drives,
                                 for a drive's torque feed-forward (docs/compensation.md); 0 at rest */
  int status;               /**< a stiffpath_status */
  int joint;                /**< offending joint (0, 1) for the STIFFPATH_JOINT_* statuses, else −1 */
  int outside_grid;         /**< 1 if p was outside the model's grid (clamped or extrapolated) */
  int laser;                /**< 1 while the laser fires (a job's command; the step copies 0) */
  double power;             /**< laser power as a fraction of full power, 0..1 (a job's command; the step copies 0) */
  int line;                 /**< the G-code line (a job's command; the step copies 0) */
} stiffpath_joint_command;

/** Settings of a whole job (stiffpath_run_job): what `stiffpath run` takes; stiffpath_default_job_options()
 *  gives the defaults every surface shares (docs/compensation.md). */
typedef struct stiffpath_job_options {
  stiffpath_options compensation; /**< gain, enabled (0: without compensation, the planned path as it is), limits,
                                       outside policy, method, damping ratio */
  int thesis;                     /**< 1: the thesis's method (bilinear model of the robot's table, quasi-static, no
                                       reference filter), overriding method, model, smooth_s and shaper (default 0) */
  double smooth_s;                /**< total smoothing width before compensation, s, 0..1; negative (default −1):
                                       0.008 when compensating, 0 without */
  int shaper;                     /**< a stiffpath_shaper (default none) */
  double max_velocity_m_s;        /**< speed limit, also of G0 (default 2) */
  double max_acceleration_m_s2;   /**< path acceleration limit (default 5 g = 49.03325) */
  double max_jerk_m_s3;           /**< jerk limit; 0 (default): the acceleration over 5 ms; negative: the
                                       acceleration times the tip's lowest natural frequency on the job */
  double rate_hz;                 /**< command rate (default 2000) */
} stiffpath_job_options;

/** Receives a job's commands one by one, in order; returning non-zero stops the job (STIFFPATH_STOPPED). */
typedef int (*stiffpath_command_sink)(const stiffpath_joint_command *command, void *user);

/** The limits of one actuated joint. */
typedef struct stiffpath_joint_limit {
  double min_rad;
  double max_rad;
  double max_velocity_rad_s;
  double max_acceleration_rad_s2;
} stiffpath_joint_limit;

/** What a controller may want to know about a robot. */
typedef struct stiffpath_robot_info {
  char name[64];                      /**< e.g. "oc-gu" (NUL-terminated, truncated if longer) */
  double moving_mass_kg;              /**< the mass whose inertia deflects the robot */
  stiffpath_joint_limit joints[2];    /**< θ1, θ2 */
} stiffpath_robot_info;

/** STIFFPATH_C_API_VERSION of the library actually linked (compare with the header's). */
STIFFPATH_C_API int stiffpath_c_api_version(void) STIFFPATH_NOEXCEPT;
/** A short English description of a status; never NULL (a static string). */
STIFFPATH_C_API const char *stiffpath_status_text(int status) STIFFPATH_NOEXCEPT;
/** The documented defaults of stiffpath_options. */
STIFFPATH_C_API stiffpath_options stiffpath_default_options(void) STIFFPATH_NOEXCEPT;
/** The documented defaults of stiffpath_job_options (those of `stiffpath run`). */
STIFFPATH_C_API stiffpath_job_options stiffpath_default_job_options(void) STIFFPATH_NOEXCEPT;

/** Loads a robot: a preset name ("oc-gu", "oc-gl", "sc-gu", "sc-gl") or the path of a robot file.
 *  Not real-time (reads files, allocates). On failure returns NULL and writes a message naming the
 *  file, the line and the offending field into `error` (NUL-terminated, truncated to error_size;
 *  error may be NULL). */
STIFFPATH_C_API stiffpath_robot *stiffpath_robot_load(const char *robot, char *error, size_t error_size) STIFFPATH_NOEXCEPT;
/** Frees a robot from stiffpath_robot_load (NULL is ignored). */
STIFFPATH_C_API void stiffpath_robot_free(stiffpath_robot *robot) STIFFPATH_NOEXCEPT;
/** Fills `info`; STIFFPATH_INVALID_ARGUMENT if either pointer is NULL. */
STIFFPATH_C_API int stiffpath_robot_get_info(const stiffpath_robot *robot, stiffpath_robot_info *info) STIFFPATH_NOEXCEPT;

/** Forward kinematics: end point p (m) of the joint angles q (rad). Real-time safe.
 *  STIFFPATH_OK or STIFFPATH_NOT_FINITE (p is then left unchanged). */
STIFFPATH_C_API int stiffpath_forward(const stiffpath_robot *robot, const double q_rad[2], double p_m[2]) STIFFPATH_NOEXCEPT;
/** Inverse kinematics in the robot's working mode: joint angles q (rad) that put the end point at
 *  p (m). Real-time safe. STIFFPATH_OK, STIFFPATH_NOT_FINITE or STIFFPATH_UNREACHABLE (outside the
 *  singularity margin; q is then left unchanged). Joint limits are not checked here. */
STIFFPATH_C_API int stiffpath_inverse(const stiffpath_robot *robot, const double p_m[2], double q_rad[2]) STIFFPATH_NOEXCEPT;

/** Creates a compensator from a robot (preset or robot file, as stiffpath_robot_load) and a
 *  compliance model: a model file written by `stiffpath fit`, a built-in name ("thesis-oc",
 *  "thesis-sc", "thesis-oc-<method>"), or NULL/"" for the robot file's own (its "compliance"
 *  entry: a model file, or its displacement table fitted at creation).
 *  options may be NULL (defaults). Not real-time. On failure returns NULL and writes the reason
 *  into `error` as stiffpath_robot_load does. */
STIFFPATH_C_API stiffpath_compensator *stiffpath_compensator_create(const char *robot, const char *model,
                                                                    const stiffpath_options *options,
                                                                    char *error, size_t error_size) STIFFPATH_NOEXCEPT;
/** Frees a compensator (NULL is ignored). */
STIFFPATH_C_API void stiffpath_compensator_free(stiffpath_compensator *compensator) STIFFPATH_NOEXCEPT;
/** The compensator's robot, for stiffpath_forward/inverse/get_info; owned by the compensator. */
STIFFPATH_C_API const stiffpath_robot *stiffpath_compensator_robot(const stiffpath_compensator *compensator) STIFFPATH_NOEXCEPT;

/** The real-time step (thesis fig. 4.3): F = −m·a, Δ = C(p)·F, p_cmd = p − k·Δ, θ = IK(p_cmd), ω, α,
 *  then the reach and joint-limit checks. Constant time, no allocation, no lock, no exception.
 *  Writes `out` and returns out->status; STIFFPATH_INVALID_ARGUMENT (out untouched) if a pointer is
 *  NULL. */
STIFFPATH_C_API int stiffpath_compensator_step(const stiffpath_compensator *compensator,
                                               const stiffpath_task_sample *sample, stiffpath_joint_command *out) STIFFPATH_NOEXCEPT;

/** The main job, exactly as `stiffpath run` makes it (not real-time: it plans, allocates and uses a second
 *  thread): plans the G-code file `gcode_path` for `robot` (a preset or robot file) with `model` (NULL/"": the
 *  robot's own), compensates every sample and hands each command, with its laser state, power and G-code line, to
 *  `sink` (from a second thread, one at a time, in order). options may be NULL (defaults). Returns STIFFPATH_OK;
 *  STIFFPATH_BAD_INPUT with the reason (file, line, column) in `error`; the status of the first refused sample
 *  (a STIFFPATH_JOINT_* or other step status) with its G-code line, time and limit in `error`; STIFFPATH_STOPPED
 *  when the sink returned non-zero; STIFFPATH_INVALID_ARGUMENT for a NULL robot, program or sink. */
STIFFPATH_C_API int stiffpath_run_job(const char *robot, const char *model, const char *gcode_path,
                                      const stiffpath_job_options *options, stiffpath_command_sink sink, void *user,
                                      char *error, size_t error_size) STIFFPATH_NOEXCEPT;

#ifdef __cplusplus
}
#endif

#endif /* STIFFPATH_STIFFPATH_H */
