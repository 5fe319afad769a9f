// Validation of the machine limits given by a user (CLI flags, configuration).
#include "stiffpath/motion/limits.hpp"

#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::motion {

namespace {
void require_positive(double value, const char* name) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw Error(fmt::format("motion limit {} must be a positive finite number, got {}", name, value));
  }
}
}  // namespace

void validate(const MotionLimits& limits) {
  require_positive(limits.max_velocity_m_s, "max_velocity_m_s");
  require_positive(limits.max_acceleration_m_s2, "max_acceleration_m_s2");
  require_positive(limits.max_jerk_m_s3, "max_jerk_m_s3");
}

}  // namespace stiffpath::motion
