// Shared parts of the compliance model contract: policies and their names.
#include "stiffpath/compliance/model.hpp"

#include <algorithm>

#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

const char* outside_words(OutsidePolicy policy) noexcept {
  switch (policy) {
    case OutsidePolicy::clamp: return "clamped to the region's edge";
    case OutsidePolicy::extrapolate: return "extrapolated";
    case OutsidePolicy::error: return "refused";
  }
  return "refused";
}

Vec2 GridBounds::clamp(const Vec2& p) const noexcept {
  return {std::clamp(p.x(), x_min, x_max), std::clamp(p.y(), y_min, y_max)};
}

void Model::compliance_batch(std::span<const Vec2> points, std::span<Mat2> out) const noexcept {
  for (std::size_t k = 0; k < points.size(); ++k) out[k] = compliance(points[k]);
}

Vec2 Model::offset(const Vec2& /*p*/) const noexcept { return Vec2::Zero(); }

}  // namespace stiffpath::compliance
