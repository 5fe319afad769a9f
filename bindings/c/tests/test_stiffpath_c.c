/* The C interface checked from C: kinematics against eqs. 2.1-2.2 written out here, the step against
 * the thesis's measured deflection and its own definitions, refusals, error texts, NULL handling and
 * (outside sanitizer builds) that a step allocates nothing. Exit status = number of failed checks. */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stiffpath/stiffpath.h"

static int failures = 0;
#define CHECK(cond)                                                             \
  do {                                                                          \
    if (!(cond)) {                                                              \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                               \
    }                                                                           \
  } while (0)
#define CHECK_NEAR(a, b, tol)                                                                          \
  do {                                                                                                 \
    const double a_ = (a), b_ = (b);                                                                   \
    if (!(fabs(a_ - b_) <= (tol))) {                                                                   \
      fprintf(stderr, "%s:%d: %s = %.17g, %s = %.17g, differ by more than %g\n", __FILE__, __LINE__, #a, \
              a_, #b, b_, (double)(tol));                                                              \
      ++failures;                                                                                      \
    }                                                                                                  \
  } while (0)

#define PI 3.14159265358979323846
static const double kLink_m = 0.150; /* l of the thesis robot, all four links (§2.2) */

/* Counting allocations: this program's malloc family replaces glibc's for the whole process. */
#ifndef STIFFPATH_TEST_NO_MALLOC_HOOK
extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
static int counting = 0;
static long allocations = 0;
void *malloc(size_t n) {
  if (counting) ++allocations;
  return __libc_malloc(n);
}
void *calloc(size_t n, size_t size) {
  if (counting) ++allocations;
  return __libc_calloc(n, size);
}
void *realloc(void *p, size_t n) {
  if (counting) ++allocations;
  return __libc_realloc(p, n);
}
#endif

/* Eq. 2.1: C = l·(e^{iθ1} + e^{iθ2}). */
static void forward_by_hand(const double q[2], double p[2]) {
  p[0] = kLink_m * (cos(q[0]) + cos(q[1]));
  p[1] = kLink_m * (sin(q[0]) + sin(q[1]));
}
/* Eq. 2.2 in the robot's working mode: θ1 = φ + η, θ2 = φ − η, η = acos(r / 2l). */
static void inverse_by_hand(const double p[2], double q[2]) {
  const double r = hypot(p[0], p[1]), phi = atan2(p[1], p[0]), eta = acos(r / (2.0 * kLink_m));
  q[0] = phi + eta;
  q[1] = phi - eta;
}

static stiffpath_task_sample sample_at(double x, double y, double ax, double ay) {
  stiffpath_task_sample s;
  memset(&s, 0, sizeof s);
  s.p_m[0] = x;
  s.p_m[1] = y;
  s.a_m_s2[0] = ax;
  s.a_m_s2[1] = ay;
  return s;
}

static void test_robot(void) {
  char error[256] = "untouched";
  stiffpath_robot *robot = stiffpath_robot_load("oc-gu", error, sizeof error);
  CHECK(robot != NULL);
  CHECK(error[0] == '\0');
  if (!robot) return;

  stiffpath_robot_info info;
  CHECK(stiffpath_robot_get_info(robot, &info) == STIFFPATH_OK);
  CHECK(strcmp(info.name, "oc-gu") == 0);
  CHECK_NEAR(info.moving_mass_kg, 3.6, 1e-15); /* thesis §4.2 */
  /* data/mechanisms/oc-gu.json: θ1 in [−45°, 135°], θ2 in [−135°, 45°], 40 rad/s, 4000 rad/s². */
  CHECK_NEAR(info.joints[0].min_rad, -45.0 * PI / 180.0, 1e-15);
  CHECK_NEAR(info.joints[0].max_rad, 135.0 * PI / 180.0, 1e-15);
  CHECK_NEAR(info.joints[1].min_rad, -135.0 * PI / 180.0, 1e-15);
  CHECK_NEAR(info.joints[1].max_rad, 45.0 * PI / 180.0, 1e-15);
  CHECK_NEAR(info.joints[0].max_velocity_rad_s, 40.0, 0.0);
  CHECK_NEAR(info.joints[1].max_acceleration_rad_s2, 4000.0, 0.0);

  const double q[2] = {60.0 * PI / 180.0, -20.0 * PI / 180.0};
  double p[2] = {0, 0}, expected[2];
  forward_by_hand(q, expected);
  CHECK(stiffpath_forward(robot, q, p) == STIFFPATH_OK);
  CHECK_NEAR(p[0], expected[0], 1e-15);
  CHECK_NEAR(p[1], expected[1], 1e-15);

  /* The whole measured workspace on a 21 × 31 grid: eq. 2.2 and the round trip. */
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 30; ++j) {
      const double point[2] = {0.172132 + 0.005 * i, -0.075 + 0.005 * j};
      double got[2], by_hand[2], back[2];
      CHECK(stiffpath_inverse(robot, point, got) == STIFFPATH_OK);
      inverse_by_hand(point, by_hand);
      CHECK_NEAR(got[0], by_hand[0], 1e-12);
      CHECK_NEAR(got[1], by_hand[1], 1e-12);
      CHECK(stiffpath_forward(robot, got, back) == STIFFPATH_OK);
      CHECK_NEAR(back[0], point[0], 1e-13);
      CHECK_NEAR(back[1], point[1], 1e-13);
    }
  }

  /* r > 2l − 5 mm (the preset's margin) and a NaN: refused, q left as it was. */
  const double far[2] = {0.2960, 0.0}, nan_point[2] = {NAN, 0.2};
  double untouched[2] = {7.0, 7.0};
  CHECK(stiffpath_inverse(robot, far, untouched) == STIFFPATH_UNREACHABLE);
  CHECK(stiffpath_inverse(robot, nan_point, untouched) == STIFFPATH_NOT_FINITE);
  CHECK(untouched[0] == 7.0 && untouched[1] == 7.0);
  const double nan_q[2] = {0.1, INFINITY};
  CHECK(stiffpath_forward(robot, nan_q, untouched) == STIFFPATH_NOT_FINITE);

  CHECK(stiffpath_robot_get_info(NULL, &info) == STIFFPATH_INVALID_ARGUMENT);
  CHECK(stiffpath_robot_get_info(robot, NULL) == STIFFPATH_INVALID_ARGUMENT);
  CHECK(stiffpath_forward(NULL, q, p) == STIFFPATH_INVALID_ARGUMENT);
  CHECK(stiffpath_inverse(robot, NULL, p) == STIFFPATH_INVALID_ARGUMENT);
  stiffpath_robot_free(robot);
  stiffpath_robot_free(NULL);
}

/* The thesis's quasi-static step (Δ = C·F, command p − k·Δ), which the step tests below check against closed forms. */
static stiffpath_options quasi_static(void) {
  stiffpath_options o = stiffpath_default_options();
  o.method = STIFFPATH_METHOD_QUASI_STATIC;
  return o;
}

static void test_step(void) {
  char error[256];
  const stiffpath_options qs = quasi_static();
  stiffpath_compensator *c = stiffpath_compensator_create("oc-gu", NULL, &qs, error, sizeof error);
  CHECK(c != NULL);
  if (!c) {
    fprintf(stderr, "create failed: %s\n", error);
    return;
  }
  const stiffpath_robot *robot = stiffpath_compensator_robot(c);
  CHECK(robot != NULL);

  /* At rest nothing is corrected (deflection relative to zero force): q = IK(p). */
  stiffpath_joint_command out;
  stiffpath_task_sample s = sample_at(0.222132, 0.0, 0.0, 0.0);
  s.t_s = 1.25;
  CHECK(stiffpath_compensator_step(c, &s, &out) == STIFFPATH_OK);
  double q_hand[2];
  inverse_by_hand(s.p_m, q_hand);
  CHECK_NEAR(out.t_s, 1.25, 0.0);
  CHECK_NEAR(out.q_rad[0], q_hand[0], 1e-12);
  CHECK_NEAR(out.q_rad[1], q_hand[1], 1e-12);
  CHECK_NEAR(out.deflection_m[0], 0.0, 0.0);
  CHECK_NEAR(out.deflection_m[1], 0.0, 0.0);
  CHECK(out.joint == -1 && out.outside_grid == 0);

  /* Table 2.3, point x3y5 (272.132, 75) mm, load step 5 in −y: F = 242.71 N, measured Δy = −1.671 mm.
   * The acceleration that makes the D'Alembert force −m·a equal that load is a = 242.71 / 3.6 m/s² in +y. */
  s = sample_at(0.272132, 0.075, 0.0, 242.7146 / 3.6);
  CHECK(stiffpath_compensator_step(c, &s, &out) == STIFFPATH_OK);
  CHECK_NEAR(out.force_N[0], 0.0, 0.0);
  CHECK_NEAR(out.force_N[1], -242.7146, 1e-12);
  CHECK_NEAR(out.deflection_m[1], -1.671e-3, 0.05e-3); /* the model's fit against one measurement: 3 % */
  /* Gain 1: p_cmd = p − Δ, and q = IK(p_cmd) by eq. 2.2. */
  CHECK_NEAR(out.command_m[0], s.p_m[0] - out.deflection_m[0], 1e-16);
  CHECK_NEAR(out.command_m[1], s.p_m[1] - out.deflection_m[1], 1e-16);
  CHECK_NEAR(out.target_m[0], s.p_m[0], 0.0);
  inverse_by_hand(out.command_m, q_hand);
  CHECK_NEAR(out.q_rad[0], q_hand[0], 1e-12);
  CHECK_NEAR(out.q_rad[1], q_hand[1], 1e-12);

  /* Δ = C(p)·F is linear in the force: twice the acceleration, twice the deflection. */
  const double d1[2] = {out.deflection_m[0], out.deflection_m[1]};
  s.a_m_s2[0] = 3.0;
  stiffpath_joint_command one, two;
  CHECK(stiffpath_compensator_step(c, &s, &one) == STIFFPATH_OK);
  s.a_m_s2[0] *= 2.0;
  s.a_m_s2[1] *= 2.0;
  CHECK(stiffpath_compensator_step(c, &s, &two) == STIFFPATH_OK);
  CHECK_NEAR(two.deflection_m[0], 2.0 * one.deflection_m[0], 1e-18);
  CHECK_NEAR(two.deflection_m[1], 2.0 * one.deflection_m[1], 1e-18);
  CHECK(fabs(one.deflection_m[1] - d1[1]) > 1e-9); /* the x force changes Δy too (coupled C) */

  /* Refusals: the command is never NaN. */
  s = sample_at(NAN, 0.0, 0.0, 0.0);
  CHECK(stiffpath_compensator_step(c, &s, &out) == STIFFPATH_NOT_FINITE);
  CHECK(out.status == STIFFPATH_NOT_FINITE && !isnan(out.q_rad[0]) && !isnan(out.q_rad[1]));
  s = sample_at(0.222132, 0.0, 0.0, 0.0);
  s.v_m_s[1] = 10.0; /* ≈ 10 / (2 l sin η) ≈ 50 rad/s per joint, over the 40 rad/s limit */
  CHECK(stiffpath_compensator_step(c, &s, &out) == STIFFPATH_JOINT_VELOCITY);
  CHECK(out.joint == 0 || out.joint == 1);
  /* By default a point more than 1 mm off the model's grid (x in 172..272 mm) is refused, not guessed. */
  s = sample_at(0.150, 0.0, 0.0, 5.0);
  CHECK(stiffpath_compensator_step(c, &s, &out) == STIFFPATH_OUTSIDE_GRID);
  CHECK(out.outside_grid == 1);
  {
    stiffpath_options clamp = stiffpath_default_options();
    clamp.outside_policy = STIFFPATH_OUTSIDE_CLAMP;
    stiffpath_compensator *clamped = stiffpath_compensator_create("oc-gu", NULL, &clamp, error, sizeof error);
    CHECK(clamped != NULL);
    if (clamped) {
      stiffpath_joint_command held;
      CHECK(stiffpath_compensator_step(clamped, &s, &held) == STIFFPATH_OK);
      CHECK(held.outside_grid == 1);
      double p_held[2];
      CHECK(stiffpath_forward(stiffpath_compensator_robot(clamped), held.q_rad, p_held) == STIFFPATH_OK);
      CHECK_NEAR(p_held[0], held.command_m[0], 1e-13);
      s = sample_at(0.2985, 0.0, 0.0, 0.0); /* beyond the stretched-out margin (295 mm) */
      CHECK(stiffpath_compensator_step(clamped, &s, &held) == STIFFPATH_UNREACHABLE);
      stiffpath_compensator_free(clamped);
    }
  }
  s = sample_at(0.222132, 0.05, 0.0, 5.0);
  CHECK(stiffpath_compensator_step(c, &s, &out) == STIFFPATH_OK);

  /* The compensator's robot is the one it was created with. */
  double p[2];
  CHECK(stiffpath_forward(robot, out.q_rad, p) == STIFFPATH_OK);
  CHECK_NEAR(p[0], out.command_m[0], 1e-13);

#ifndef STIFFPATH_TEST_NO_MALLOC_HOOK
  s = sample_at(0.25, 0.03, 12.0, -7.0);
  s.v_m_s[0] = 0.4;
  s.j_m_s3[1] = 900.0;
  allocations = 0;
  counting = 1;
  for (int i = 0; i < 1000; ++i) {
    s.p_m[0] += 1e-5;
    (void)stiffpath_compensator_step(c, &s, &out);
  }
  counting = 0;
  CHECK(allocations == 0);
  /* ... while the hook does see the library's allocations (operator new of libstdc++ calls malloc). */
  counting = 1;
  stiffpath_robot_free(stiffpath_robot_load("oc-gu", NULL, 0));
  counting = 0;
  CHECK(allocations > 0);
#endif

  CHECK(stiffpath_compensator_step(NULL, &s, &out) == STIFFPATH_INVALID_ARGUMENT);
  CHECK(stiffpath_compensator_step(c, NULL, &out) == STIFFPATH_INVALID_ARGUMENT);
  CHECK(stiffpath_compensator_step(c, &s, NULL) == STIFFPATH_INVALID_ARGUMENT);
  CHECK(stiffpath_compensator_robot(NULL) == NULL);
  stiffpath_compensator_free(c);
  stiffpath_compensator_free(NULL);
}

static void test_options(void) {
  char error[256];
  stiffpath_options o = stiffpath_default_options();
  CHECK(o.gain == 1.0 && o.enabled == 1 && o.check_limits == 1 && o.outside_policy == STIFFPATH_OUTSIDE_MODEL_DEFAULT);
  CHECK(o.method == STIFFPATH_METHOD_DYNAMIC); /* as every surface's default */
  o = quasi_static();

  stiffpath_compensator *full = stiffpath_compensator_create("oc-gu", "thesis-oc", &o, error, sizeof error);
  o.gain = 0.5;
  stiffpath_compensator *half = stiffpath_compensator_create("oc-gu", "thesis-oc", &o, error, sizeof error);
  o.gain = 1.0;
  o.enabled = 0;
  stiffpath_compensator *off = stiffpath_compensator_create("oc-gu", "thesis-oc", &o, error, sizeof error);
  o = stiffpath_default_options();
  o.outside_policy = STIFFPATH_OUTSIDE_ERROR;
  stiffpath_compensator *strict = stiffpath_compensator_create("oc-gu", NULL, &o, error, sizeof error);
  CHECK(full && half && off && strict);
  if (full && half && off && strict) {
    const stiffpath_task_sample s = sample_at(0.2, -0.04, -20.0, 15.0);
    stiffpath_joint_command f, h, n;
    CHECK(stiffpath_compensator_step(full, &s, &f) == STIFFPATH_OK);
    CHECK(stiffpath_compensator_step(half, &s, &h) == STIFFPATH_OK);
    CHECK(stiffpath_compensator_step(off, &s, &n) == STIFFPATH_OK);
    CHECK_NEAR(h.command_m[0], s.p_m[0] - 0.5 * f.deflection_m[0], 1e-16);
    CHECK_NEAR(h.command_m[1], s.p_m[1] - 0.5 * f.deflection_m[1], 1e-16);
    double q_hand[2];
    inverse_by_hand(s.p_m, q_hand);
    CHECK_NEAR(n.q_rad[0], q_hand[0], 1e-12);
    CHECK_NEAR(n.q_rad[1], q_hand[1], 1e-12);
    CHECK(fabs(f.q_rad[0] - n.q_rad[0]) > 1e-5); /* 15-25 m/s² moves the command by ~0.1 mm: visible */
    /* The load torque does the work of the inertial force: τ·ω = (m·a)·v when p_cmd = p (ω = J⁻¹·v). */
    stiffpath_task_sample moving = s;
    moving.v_m_s[0] = 0.31;
    moving.v_m_s[1] = -0.17;
    CHECK(stiffpath_compensator_step(off, &moving, &n) == STIFFPATH_OK);
    const double power_W = 3.6 * (s.a_m_s2[0] * moving.v_m_s[0] + s.a_m_s2[1] * moving.v_m_s[1]);
    CHECK_NEAR(n.load_torque_Nm[0] * n.qd_rad_s[0] + n.load_torque_Nm[1] * n.qd_rad_s[1], power_W, 1e-12);
    CHECK(fabs(n.load_torque_Nm[0]) > 1e-3 && fabs(n.load_torque_Nm[1]) > 1e-3);
    const stiffpath_task_sample outside = sample_at(0.150, 0.0, 0.0, 5.0);
    CHECK(stiffpath_compensator_step(strict, &outside, &f) == STIFFPATH_OUTSIDE_GRID);
  }
  stiffpath_compensator_free(full);
  stiffpath_compensator_free(half);
  stiffpath_compensator_free(off);
  stiffpath_compensator_free(strict);
}

/* LinuxCNC's stiffpathcomp runs the step at gain 1 and applies its live gain k as IK(p − k·Δ) with that
 * step's Δ (Δ does not depend on the gain): the same joint angles as a compensator created with gain k. */
static void test_gain_from_the_full_step(void) {
  char error[256];
  const stiffpath_options qs = quasi_static();
  stiffpath_compensator *full = stiffpath_compensator_create("oc-gu", NULL, &qs, error, sizeof error);
  CHECK(full != NULL);
  if (!full) return;
  const stiffpath_robot *robot = stiffpath_compensator_robot(full);
  double worst_rad = 0.0, largest_rad = 0.0;
  for (int g = 1; g <= 3; ++g) {
    stiffpath_options o = quasi_static();
    o.gain = 0.25 * g;
    stiffpath_compensator *part = stiffpath_compensator_create("oc-gu", NULL, &o, error, sizeof error);
    CHECK(part != NULL);
    if (!part) continue;
    for (int i = 0; i <= 10; ++i) {
      for (int j = 0; j <= 10; ++j) {
        for (int d = 0; d < 8; ++d) {
          const double a = 2.0 * 9.80665, angle = d * PI / 4.0;
          const stiffpath_task_sample s = sample_at(0.172132 + 0.01 * i, -0.075 + 0.015 * j, a * cos(angle), a * sin(angle));
          stiffpath_joint_command f, p;
          CHECK(stiffpath_compensator_step(full, &s, &f) == STIFFPATH_OK);
          CHECK(stiffpath_compensator_step(part, &s, &p) == STIFFPATH_OK);
          const double target[2] = {s.p_m[0] - o.gain * f.deflection_m[0], s.p_m[1] - o.gain * f.deflection_m[1]};
          double q[2], q0[2];
          CHECK(stiffpath_inverse(robot, target, q) == STIFFPATH_OK);
          CHECK(stiffpath_inverse(robot, s.p_m, q0) == STIFFPATH_OK);
          for (int k = 0; k < 2; ++k) {
            worst_rad = fmax(worst_rad, fabs(q[k] - p.q_rad[k]));
            largest_rad = fmax(largest_rad, fabs(p.q_rad[k] - q0[k]));
          }
        }
      }
    }
    stiffpath_compensator_free(part);
  }
  CHECK(worst_rad <= 1e-13);
  CHECK(largest_rad > 1e-4); /* 2 g moves the command by a visible amount */
  stiffpath_compensator_free(full);
}

static void test_errors(const char *scratch_dir) {
  char error[512];
  CHECK(stiffpath_robot_load("/nonexistent/robot.json", error, sizeof error) == NULL);
  CHECK(strstr(error, "/nonexistent/robot.json") != NULL);
  CHECK(stiffpath_robot_load(NULL, error, sizeof error) == NULL);
  CHECK(strlen(error) > 0);
  CHECK(stiffpath_robot_load("", NULL, 0) == NULL); /* no buffer: still no crash */

  /* A robot file with a negative link length: the message names the file and the field. */
  char path[1024];
  snprintf(path, sizeof path, "%s/bad_robot.json", scratch_dir);
  FILE *f = fopen(path, "w");
  CHECK(f != NULL);
  if (f) {
    fputs("{\"name\": \"bad\", \"description\": \"\", \"left_actuator_mm\": [0, 0], \"right_actuator_mm\": [0, 0],\n"
          " \"left_proximal_mm\": -150.0, \"right_proximal_mm\": 150, \"left_distal_mm\": 150, \"right_distal_mm\": 150,\n"
          " \"elbows\": [1, -1],\n"
          " \"moving_mass_kg\": 3.6, \"cg\": {\"label\": \"G_U\", \"height_above_G_mm\": 35.9},\n"
          " \"measurement\": {\"UG_mm\": 69.0, \"UL_mm\": 160.0},\n"
          " \"joints\": [{\"name\": \"theta1\", \"min_deg\": -45, \"max_deg\": 135, \"max_velocity_rad_s\": 40,\n"
          "              \"max_acceleration_rad_s2\": 4000},\n"
          "            {\"name\": \"theta2\", \"min_deg\": -135, \"max_deg\": 45, \"max_velocity_rad_s\": 40,\n"
          "             \"max_acceleration_rad_s2\": 4000}],\n"
          " \"singularity_margin\": {\"min_distance_mm\": 5.0, \"max_condition_number\": 8.0},\n"
          " \"compliance\": {\"table\": \"builtin:thesis/displacements.csv\"}}\n",
          f);
    fclose(f);
    CHECK(stiffpath_compensator_create(path, NULL, NULL, error, sizeof error) == NULL);
    CHECK(strstr(error, "bad_robot.json") != NULL);
    CHECK(strstr(error, "left_proximal_mm") != NULL);
    CHECK(strstr(error, "-150.0") != NULL);
    remove(path);
  }

  /* A robot file nested 20 000 objects deep (120 kB): NULL and the limit, not a crash of the caller. */
  snprintf(path, sizeof path, "%s/deep_robot.json", scratch_dir);
  f = fopen(path, "w");
  CHECK(f != NULL);
  if (f) {
    for (int k = 0; k < 20000; ++k) fputs("{\"a\":", f);
    fputs("1", f);
    for (int k = 0; k < 20000; ++k) fputc('}', f);
    fclose(f);
    CHECK(stiffpath_robot_load(path, error, sizeof error) == NULL);
    CHECK(strstr(error, "deep_robot.json:1:321") != NULL); /* the 65th "{", 5 bytes per level */
    CHECK(strstr(error, "LIMIT: nested more than 64 levels") != NULL);
    CHECK(stiffpath_compensator_create(path, NULL, NULL, error, sizeof error) == NULL);
    CHECK(stiffpath_compensator_create("oc-gu", path, NULL, error, sizeof error) == NULL);
    CHECK(strstr(error, "LIMIT") != NULL);
    remove(path);
  }

  CHECK(stiffpath_compensator_create("oc-gu", "no-such-model", NULL, error, sizeof error) == NULL);
  CHECK(strstr(error, "no-such-model") != NULL);
  stiffpath_options o = stiffpath_default_options();
  o.gain = -1.0;
  CHECK(stiffpath_compensator_create("oc-gu", NULL, &o, error, sizeof error) == NULL);
  CHECK(strstr(error, "gain") != NULL);
  o = stiffpath_default_options();
  o.outside_policy = 9;
  CHECK(stiffpath_compensator_create("oc-gu", NULL, &o, error, sizeof error) == NULL);
  CHECK(strstr(error, "outside_policy") != NULL);

  /* A short buffer receives the start of the message, NUL-terminated. */
  char tiny[8];
  memset(tiny, 'x', sizeof tiny);
  CHECK(stiffpath_robot_load("/nonexistent/robot.json", tiny, sizeof tiny) == NULL);
  CHECK(strlen(tiny) == sizeof tiny - 1);
}

static void test_status_text(void) {
  for (int s = STIFFPATH_OK; s <= STIFFPATH_INVALID_ARGUMENT; ++s) {
    const char *text = stiffpath_status_text(s);
    CHECK(text != NULL && strlen(text) > 1);
    for (int t = STIFFPATH_OK; t < s; ++t) CHECK(strcmp(text, stiffpath_status_text(t)) != 0);
  }
  CHECK(strcmp(stiffpath_status_text(99), "unknown status") == 0);
  CHECK(strcmp(stiffpath_status_text(-1), "unknown status") == 0);
}

int main(int argc, char **argv) {
  CHECK(stiffpath_c_api_version() == STIFFPATH_C_API_VERSION);
  test_robot();
  test_step();
  test_options();
  test_gain_from_the_full_step();
  test_errors(argc > 1 ? argv[1] : ".");
  test_status_text();
  if (failures) fprintf(stderr, "%d check(s) failed\n", failures);
  else printf("all checks passed\n");
  return failures ? 1 : 0;
}
