// The twin's compensation variants as jobs: the same JobSpec presets `run` and `run --thesis` use.
#include "stiffpath/simulation/compensation_variant.hpp"

namespace stiffpath::simulation {

job::JobSpec variant_job(const kinematics::Robot& robot, CompensationVariant variant) {
  job::JobSpec spec = variant == CompensationVariant::thesis ? job::thesis_job(robot) : job::default_job(robot);
  spec.compensate = variant != CompensationVariant::without;
  return spec;
}

std::optional<compliance::FitMethod> compensation_fit_method(CompensationVariant variant) {
  if (variant == CompensationVariant::thesis) return compliance::FitMethod::bilinear;
  return std::nullopt;
}

}  // namespace stiffpath::simulation
