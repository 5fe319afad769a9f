/* A user's C program: the installed C interface's inverse and forward kinematics and one compensation step. */
#include <stdio.h>

#include <stiffpath/stiffpath.h>

int main(void) {
  char error[512];
  stiffpath_compensator *c = stiffpath_compensator_create("oc-gu", NULL, NULL, error, sizeof error);
  if (!c) {
    fprintf(stderr, "%s\n", error);
    return 2;
  }
  const double p[2] = {0.222132, 0.0375};
  double q[2], back[2];
  if (stiffpath_inverse(stiffpath_compensator_robot(c), p, q) != STIFFPATH_OK ||
      stiffpath_forward(stiffpath_compensator_robot(c), q, back) != STIFFPATH_OK) return 1;
  /* Table 2.3, x3y5 under 242.71 N in -y: the D'Alembert force of a = 242.71 / 3.6 m/s² in +y. */
  stiffpath_task_sample s = {0.0, {0.272132, 0.075}, {0, 0}, {0, 242.7146 / 3.6}, {0, 0}, {0, 0}};
  stiffpath_joint_command out;
  if (stiffpath_compensator_step(c, &s, &out) != STIFFPATH_OK) return 1;
  printf("x_mm=%.3f y_mm=%.3f dy_um=%.0f\n", back[0] * 1e3, back[1] * 1e3, out.deflection_m[1] * 1e6);
  stiffpath_compensator_free(c);
  return 0;
}
