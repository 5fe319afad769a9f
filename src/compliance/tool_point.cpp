// Tool-point prediction from the translational model at G plus the angular deflections' lever arm.
#include "stiffpath/compliance/tool_point.hpp"

#include <cmath>
#include <fmt/format.h>

#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

std::unique_ptr<GridModel> make_angular_model(const std::vector<PointFit>& fits, const std::string& source) {
  std::vector<Vec2> positions;
  for (const auto& f : fits) positions.push_back(f.position);
  return build_grid_model(FitMethod::bilinear, positions, [&](std::size_t k) {
    const auto a = fits[k].angular_compliance();
    if (!a) {
      throw Error(SourceLocation{source},
                  fmt::format("point {}: fewer than two usable load steps of angular deflection (rx_deg, ry_deg) "
                              "along x and along y",
                              fits[k].id));
    }
    return GridNode{fits[k].id, *a, Vec2::Zero(), nlohmann::json::object()};
  }, source);
}

ToolPointModel::ToolPointModel(std::shared_ptr<const Model> at_G, std::shared_ptr<const GridModel> angular,
                               double distance_below_G_m)
    : at_G_(std::move(at_G)), angular_(std::move(angular)), d_(distance_below_G_m) {
  if (!at_G_ || !angular_) throw Error("tool-point model needs a translational and an angular model");
  if (!std::isfinite(d_)) throw Error("tool-point distance must be finite");
  set_outside_policy(at_G_->outside_policy());
  set_zero_force(at_G_->zero_force());
}

Mat2 ToolPointModel::lever(const Vec2& p) const noexcept {
  const Mat2 a = angular_->compliance(p);
  Mat2 l;
  l << -a(1, 0), -a(1, 1), a(0, 0), a(0, 1);
  return d_ * l;
}

Mat2 ToolPointModel::compliance(const Vec2& p) const noexcept { return at_G_->compliance(p) + lever(p); }

nlohmann::json ToolPointModel::parameters() const {
  nlohmann::json out = model_parameters(*at_G_);
  out["tool_point"] = {{"distance_below_G_mm", d_ * 1e3}, {"angular", angular_->parameters()}};
  return out;
}

}  // namespace stiffpath::compliance
