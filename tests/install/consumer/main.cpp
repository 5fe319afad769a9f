// A user's program: inverse then forward kinematics, and a built-in compliance model, via the installed library.
#include <cstdio>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/kinematics/robot.hpp"

int main() {
  const auto robot = stiffpath::kinematics::load_robot("oc-gu").five_bar();
  const auto p = robot.forward(robot.inverse({0.222132, 0.0375}));
  const auto model = stiffpath::compliance::load_model("thesis-oc");
  const auto d = model.model->predict({0.272132, 0.075}, {0.0, -242.71});
  std::printf("x_mm=%.3f y_mm=%.3f dy_um=%.0f\n", p.x() * 1e3, p.y() * 1e3, d.y() * 1e6);
  return 0;
}
