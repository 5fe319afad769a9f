// libFuzzer harness: the C interface's robot loader (stiffpath_robot_load on a file), which must return NULL, never crash.
#include <cmath>
#include <cstdlib>

#include "fuzz_input.hpp"
#include "stiffpath/stiffpath.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = stiffpath::fuzz::as_file(data, size, "-robot.json");
  char error[512];
  stiffpath_robot* robot = stiffpath_robot_load(path.c_str(), error, sizeof error);
  if (robot == nullptr) {
    if (error[0] == '\0') std::abort();  // a refusal always says why
    return 0;
  }
  // A robot that loads answers every call: its info, and forward / inverse kinematics that agree.
  stiffpath_robot_info info;
  if (stiffpath_robot_get_info(robot, &info) != STIFFPATH_OK || !(info.moving_mass_kg > 0.0)) std::abort();
  const double q[2] = {0.5 * (info.joints[0].min_rad + info.joints[0].max_rad),
                       0.5 * (info.joints[1].min_rad + info.joints[1].max_rad)};
  double p[2] = {0.0, 0.0}, back[2] = {0.0, 0.0};
  if (stiffpath_forward(robot, q, p) == STIFFPATH_OK && std::isfinite(p[0]) && std::isfinite(p[1])) {
    (void)stiffpath_inverse(robot, p, back);
  }
  stiffpath_robot_free(robot);
  return 0;
}
