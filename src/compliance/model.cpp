// Shared parts of the compliance model contract: policies and their names.
#include "stiffpath/compliance/model.hpp"

#include <algorithm>

#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

const char* to_string(OutsidePolicy policy) noexcept {
  switch (policy) {
    case OutsidePolicy::clamp: return "clamp";
    case OutsidePolicy::extrapolate: return "extrapolate";
    case OutsidePolicy::error: return "error";
  }
  return "?";
}

const char* to_string(ZeroForce mode) noexcept {
  return mode == ZeroForce::relative ? "relative" : "thesis-raw";
}

OutsidePolicy parse_outside_policy(const std::string& text) {
  if (text == "clamp") return OutsidePolicy::clamp;
  if (text == "extrapolate") return OutsidePolicy::extrapolate;
  if (text == "error") return OutsidePolicy::error;
  throw Error("outside-grid policy '" + text + "' is not one of clamp, extrapolate, error");
}

ZeroForce parse_zero_force(const std::string& text) {
  if (text == "relative") return ZeroForce::relative;
  if (text == "thesis-raw") return ZeroForce::thesis_raw;
  throw Error("zero-force mode '" + text + "' is not one of relative, thesis-raw");
}

Vec2 GridBounds::clamp(const Vec2& p) const noexcept {
  return {std::clamp(p.x(), x_min, x_max), std::clamp(p.y(), y_min, y_max)};
}

void Model::compliance_batch(std::span<const Vec2> points, std::span<Mat2> out) const noexcept {
  for (std::size_t k = 0; k < points.size(); ++k) out[k] = compliance(points[k]);
}

Vec2 Model::offset(const Vec2& /*p*/) const noexcept { return Vec2::Zero(); }

}  // namespace stiffpath::compliance
