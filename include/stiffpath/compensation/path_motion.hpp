// Motion along a path from its arc length's time derivatives: the chain rule on a line or an arc.
#pragma once

#include <array>

#include "stiffpath/compensation/samples.hpp"

namespace stiffpath::compensation {

//! A path's local geometry at one arc length, on a piece of constant curvature (a line or an arc).
struct PathGeometry {
  Vec2 position_m = Vec2::Zero();
  Vec2 tangent = Vec2::UnitX();  //!< unit tangent T in the direction of motion
  double curvature_1_m = 0.0;    //!< signed curvature κ (1/m), > 0 turning left; constant along the piece
};

//! The point and its first five time derivatives for a motion along the piece whose arc length follows σ(t), given
//! σ, σ̇ … σ⁽⁵⁾ (only σ̇ … σ⁽⁵⁾ are used: the point is `geometry`'s). With N the left normal, T' = κN and N' = −κT:
//!   ṗ = σ̇T,  p̈ = σ̈T + κσ̇²N,  p⃛ = (σ⃛ − κ²σ̇³)T + 3κσ̇σ̈N,
//!   p⁽⁴⁾ = (σ⁽⁴⁾ − 6κ²σ̇²σ̈)T + κ(4σ̇σ⃛ + 3σ̈² − κ²σ̇⁴)N,
//!   p⁽⁵⁾ = (σ⁽⁵⁾ − 15κ²σ̇σ̈² − 10κ²σ̇²σ⃛ + κ⁴σ̇⁵)T + κ(10σ̈σ⃛ + 5σ̇σ⁽⁴⁾ − 10κ²σ̇³σ̈)N.
std::array<Vec2, 6> motion_along(const PathGeometry& geometry, const std::array<double, 6>& sigma) noexcept;

}  // namespace stiffpath::compensation
