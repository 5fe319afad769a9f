// A smooth 2×2 field sampled once on a square lattice and read back by Catmull–Rom bicubic interpolation (constant time).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "stiffpath/compliance/model.hpp"

namespace stiffpath::compliance {

//! `field` sampled on a square lattice of `spacing_m` over `region` (plus one node of stencil beyond it
//! on every side), read by Catmull–Rom bicubic interpolation: C¹, exact for fields linear in x and y,
//! error O(h³·|∂³C|). Every cell is checked at its centre when the lattice is made; a cell that reads more
//! than `tolerance` (relative, Frobenius; default 10⁻⁶) off there is marked, and covers() is false in it and outside `region`,
//! so that callers evaluate the field itself wherever the lattice cannot follow it. For fields that are
//! expensive to evaluate and smooth on the lattice's scale. Filled in the constructor, only read after
//! (thread-safe to read); read() and covers() are noexcept and allocation-free.
class FieldLattice {
 public:
  FieldLattice(const std::function<Mat2(const Vec2&)>& field, const GridBounds& region, double spacing_m,
               double tolerance = 1e-6);

  //! Whether the lattice serves p: p inside the region and in a cell the lattice follows.
  [[nodiscard]] bool covers(const Vec2& p) const noexcept;
  //! Where covers(p): writes the interpolated field at p to `out` and returns true; else false.
  [[nodiscard]] bool read(const Vec2& p, Mat2& out) const noexcept;

  [[nodiscard]] const GridBounds& region() const noexcept { return region_; }
  [[nodiscard]] double spacing_m() const noexcept { return h_; }
  [[nodiscard]] std::size_t nodes() const noexcept { return values_.size(); }
  //! Cells the lattice does not follow (left to the field).
  [[nodiscard]] std::size_t exact_cells() const noexcept;

 private:
  GridBounds region_;
  double h_;
  double inverse_h_ = 0.0;
  double x0_ = 0.0, y0_ = 0.0;  // the lattice's node (0, 0), one spacing outside the region's corner
  std::size_t nx_ = 0, ny_ = 0;
  std::vector<Mat2> values_;       // node (i, j) at (x0 + i·h, y0 + j·h), index i·ny + j
  std::vector<std::uint8_t> exact_;  // per cell (i, j), 1 ≤ i ≤ nx − 3: not followed
  [[nodiscard]] std::size_t cell_x(double u) const noexcept;
  [[nodiscard]] std::size_t cell_y(double v) const noexcept;
  [[nodiscard]] Mat2 interpolate(std::size_t i, std::size_t j, double tx, double ty) const noexcept;
};

}  // namespace stiffpath::compliance
