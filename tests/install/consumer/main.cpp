// A user's program through the installed library's module headers: inverse then forward kinematics, a built-in
// compliance model, and the main job as a value (planned, compensated and summarised in memory).
#include <cstdio>

#include "stiffpath/calibration.hpp"
#include "stiffpath/compensation.hpp"
#include "stiffpath/compliance.hpp"
#include "stiffpath/core.hpp"
#include "stiffpath/evaluation.hpp"
#include "stiffpath/job.hpp"
#include "stiffpath/kinematics.hpp"
#include "stiffpath/measurement.hpp"
#include "stiffpath/motion.hpp"
#include "stiffpath/simulation.hpp"

int main() {
  const auto robot = stiffpath::kinematics::load_robot("oc-gu").five_bar();
  const auto p = robot.forward(robot.inverse({0.222132, 0.0375}));
  const auto model = stiffpath::compliance::load_model("thesis-oc");
  const auto d = model.model->predict({0.272132, 0.075}, {0.0, -242.71});
  std::printf("x_mm=%.3f y_mm=%.3f dy_um=%.0f\n", p.x() * 1e3, p.y() * 1e3, d.y() * 1e6);
  const auto job = stiffpath::job::prepare(stiffpath::job::default_job(stiffpath::kinematics::load_robot("oc-gu")),
                                           stiffpath::job::Program::text("G21 G90 G61\nG0 X200 Y0\nG1 X220 F6000\nM2\n", "line"));
  const auto summary = stiffpath::job::run(job, nullptr);
  std::printf("samples=%llu\n", static_cast<unsigned long long>(summary.samples));
  return summary.samples > 0 ? 0 : 1;
}
