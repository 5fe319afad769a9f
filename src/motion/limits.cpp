// Validation of the machine limits given by a user (CLI flags, configuration).
#include "stiffpath/motion/limits.hpp"

#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::motion {

namespace {
void require_within(double value, double low, double high, const char* name) {
  if (!(value >= low && value <= high)) {  // NaN fails too
    throw Error(fmt::format("motion limit {} must be within [{:g}, {:g}], got {}", name, low, high, value));
  }
}
}  // namespace

void validate(const MotionLimits& limits) {
  require_within(limits.max_velocity_m_s, min_velocity_limit_m_s, max_velocity_limit_m_s, "max_velocity_m_s");
  require_within(limits.max_acceleration_m_s2, min_acceleration_limit_m_s2, max_acceleration_limit_m_s2,
                 "max_acceleration_m_s2");
  require_within(limits.max_jerk_m_s3, min_jerk_limit_m_s3, max_jerk_limit_m_s3, "max_jerk_m_s3");
}

}  // namespace stiffpath::motion
