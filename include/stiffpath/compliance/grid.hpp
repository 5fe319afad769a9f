// A rectangular (tensor-product) grid of measurement points and cell lookup for bilinear interpolation.
#pragma once

#include <string>
#include <vector>

#include "stiffpath/compliance/model.hpp"

namespace stiffpath::compliance {

//! Grid lines xs (ascending, ≥ 2) × ys (ascending, ≥ 2), m. Node (i, j) is (xs[i], ys[j]).
struct Grid {
  std::vector<double> xs;
  std::vector<double> ys;

  //! Builds the grid from scattered positions; every xs × ys combination must appear exactly once.
  //! `node_of[k]` receives the node index i·ys.size() + j of position k. Throws stiffpath::Error
  //! naming `source` and the missing or repeated node.
  static Grid from_positions(const std::vector<Vec2>& positions, std::vector<int>& node_of, const std::string& source);

  [[nodiscard]] int node(int i, int j) const noexcept { return i * static_cast<int>(ys.size()) + j; }
  [[nodiscard]] GridBounds bounds() const noexcept { return {xs.front(), xs.back(), ys.front(), ys.back()}; }

  //! Cell lower index and local coordinates (tx, ty) of p for bilinear interpolation (eq. 4.12). Inside
  //! the grid t ∈ [0, 1]; outside, the nearest edge cell with t beyond [0, 1] (extrapolation).
  void locate(const Vec2& p, int& i, int& j, double& tx, double& ty) const noexcept;
};

}  // namespace stiffpath::compliance
