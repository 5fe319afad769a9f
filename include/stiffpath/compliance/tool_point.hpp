// Moving a prediction from G to the laser's tool point using the measured angular deflections.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <memory>
#include <vector>

#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/compliance/point_fit.hpp"

namespace stiffpath::compliance {

//! Angular compliance A(p) = ∂(rx, ry)/∂(Fx, Fy) in rad/N on the grid, bilinear between points, from
//! the per-point fits of the angular deflections (thesis tables 3.4–3.7). Throws stiffpath::Error
//! naming a point without angular data.
std::unique_ptr<GridModel> make_angular_model(const std::vector<PointFit>& fits, const std::string& source);

//! A translational model moved to a tool point at `distance_below_G_m` below G:
//! Δp_tool = Δp_G + Δθ × r with r = (0, 0, −d), i.e. Δx_tool = Δx_G − d·Δθy, Δy_tool = Δy_G + d·Δθx.
class ToolPointModel final : public Model {
 public:
  ToolPointModel(std::shared_ptr<const Model> at_G, std::shared_ptr<const GridModel> angular, double distance_below_G_m);

  [[nodiscard]] std::optional<FitMethod> method() const noexcept override { return at_G_->method(); }
  [[nodiscard]] std::string description() const override { return at_G_->description() + " at the tool point"; }
  [[nodiscard]] Mat2 compliance(const Vec2& p) const noexcept override;
  [[nodiscard]] Vec2 offset(const Vec2& p) const noexcept override { return at_G_->offset(p); }
  [[nodiscard]] GridBounds bounds() const noexcept override { return at_G_->bounds(); }
  //! Its parameters and fit statistics as JSON, as model files hold them (compliance::model_parameters).
  [[nodiscard]] nlohmann::json parameters() const;

  //! The part added by the rotation: d·[−A21 −A22; A11 A12] (m/N).
  [[nodiscard]] Mat2 lever(const Vec2& p) const noexcept;

 private:
  std::shared_ptr<const Model> at_G_;
  std::shared_ptr<const GridModel> angular_;
  double d_;
};

}  // namespace stiffpath::compliance
