// The JobSpec's named presets: the defaults for a robot, and the thesis's method.
#include "stiffpath/job/job_spec.hpp"

namespace stiffpath::job {

JobSpec default_job(kinematics::Robot robot) {
  JobSpec spec;
  spec.robot = std::move(robot);
  return spec;
}

JobSpec thesis_job(kinematics::Robot robot) {
  JobSpec spec = default_job(std::move(robot));
  spec.model.request.method = compliance::FitMethod::bilinear;
  spec.method = compensation::Method::quasi_static;
  spec.smooth_s = 0.0;
  spec.shaper = compensation::FilterKind::none;
  return spec;
}

double smoothing_s(const JobSpec& spec) noexcept {
  return spec.smooth_s.value_or(spec.compensate ? compensation::kDefaultSmoothing_s : 0.0);
}

}  // namespace stiffpath::job
