/* run_job: the main job through the C interface (stiffpath_run_job), each command written exactly (%.17g), so that a
 * test can hold it against the CLI, Python and MATLAB/Octave. Usage: run_job ROBOT GCODE OUT.csv [thesis|plain] */
#include <stdio.h>
#include <string.h>

#include "stiffpath/stiffpath.h"

static int write_command(const stiffpath_joint_command *c, void *user) {
  FILE *out = (FILE *)user;
  return fprintf(out, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%.17g,%d\n", c->t_s, c->q_rad[0], c->q_rad[1],
                 c->qd_rad_s[0], c->qd_rad_s[1], c->qdd_rad_s2[0], c->qdd_rad_s2[1], c->laser, c->power, c->line) < 0;
}

int main(int argc, char **argv) {
  if (argc != 4 && argc != 5) {
    fprintf(stderr, "usage: run_job ROBOT GCODE OUT.csv [thesis|plain]\n");
    return 2;
  }
  stiffpath_job_options options = stiffpath_default_job_options();
  if (argc == 5 && strcmp(argv[4], "thesis") == 0) options.thesis = 1;
  if (argc == 5 && strcmp(argv[4], "plain") == 0) options.compensation.enabled = 0;
  FILE *out = fopen(argv[3], "w");
  if (out == NULL) {
    perror(argv[3]);
    return 2;
  }
  fprintf(out, "t_s,theta1_rad,theta2_rad,omega1_rad_s,omega2_rad_s,alpha1_rad_s2,alpha2_rad_s2,laser,power,line\n");
  char error[1024];
  const int status = stiffpath_run_job(argv[1], NULL, argv[2], &options, write_command, out, error, sizeof error);
  fclose(out);
  if (status != STIFFPATH_OK) {
    fprintf(stderr, "error: %s (%s)\n", error, stiffpath_status_text(status));
    return 2;
  }
  return 0;
}
