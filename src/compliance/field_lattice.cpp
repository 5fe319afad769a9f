// A 2×2 field on a square lattice, read back by Catmull–Rom bicubic interpolation.
#include "stiffpath/compliance/field_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

namespace {

// More nodes than this is a mistake (10⁶ nodes = 32 MB and seconds of evaluations of an expensive field).
constexpr std::size_t kMaxNodes = 1'000'000;
// Catmull–Rom weights of the nodes −1, 0, 1, 2 at the fraction t ∈ [0, 1) of a cell.
void catmull_rom(double t, double w[4]) noexcept {
  const double t2 = t * t, t3 = t2 * t;
  w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
  w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
  w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
  w[3] = 0.5 * (t3 - t2);
}

// The cell [i, i+1] with 1 ≤ i ≤ n − 3 that holds the lattice coordinate w (the region starts at node 1,
// up to rounding); its 4-node stencil is i − 1 … i + 2.
std::size_t cell_of(double w, std::size_t n) noexcept {
  return std::clamp(static_cast<std::size_t>(std::max(w, 1.0)), std::size_t{1}, n - 3);
}

}  // namespace

FieldLattice::FieldLattice(const std::function<Mat2(const Vec2&)>& field, const GridBounds& region, double spacing_m,
                           double tolerance)
    : region_(region), h_(spacing_m), inverse_h_(1.0 / spacing_m) {
  if (!(std::isfinite(h_) && h_ > 0.0)) throw Error(fmt::format("field lattice: spacing {} m must be positive", h_));
  const double width = region.x_max - region.x_min, height = region.y_max - region.y_min;
  if (!(std::isfinite(width) && std::isfinite(height) && width > 0.0 && height > 0.0)) {
    throw Error(fmt::format("field lattice: empty region [{}, {}] × [{}, {}] m", region.x_min, region.x_max,
                            region.y_min, region.y_max));
  }
  // Cells cover the region; one more node on each side carries the stencil of the border cells.
  const double cells_x = std::ceil(width / h_), cells_y = std::ceil(height / h_);
  if (!((cells_x + 3.0) * (cells_y + 3.0) <= static_cast<double>(kMaxNodes))) {
    throw Error(fmt::format("field lattice: {:.0f} × {:.0f} cells of {} m exceed {} nodes", cells_x, cells_y, h_,
                            kMaxNodes));
  }
  nx_ = static_cast<std::size_t>(cells_x) + 3;
  ny_ = static_cast<std::size_t>(cells_y) + 3;
  x0_ = region.x_min - h_;
  y0_ = region.y_min - h_;
  values_.resize(nx_ * ny_);
  for (std::size_t i = 0; i < nx_; ++i) {
    for (std::size_t j = 0; j < ny_; ++j) {
      values_[i * ny_ + j] = field(Vec2(x0_ + static_cast<double>(i) * h_, y0_ + static_cast<double>(j) * h_));
    }
  }
  // Where the field is not smooth on the lattice's scale (near a reach limit, where a structure turns
  // singular) a cell's centre, its farthest point from the nodes, reads off; such cells are left to the field.
  exact_.assign((nx_ - 3) * (ny_ - 3), 0);
  for (std::size_t i = 1; i + 2 < nx_; ++i) {
    for (std::size_t j = 1; j + 2 < ny_; ++j) {
      const Vec2 centre(x0_ + (static_cast<double>(i) + 0.5) * h_, y0_ + (static_cast<double>(j) + 0.5) * h_);
      const Mat2 want = field(centre), got = interpolate(i, j, 0.5, 0.5);
      const bool smooth = want.allFinite() && got.allFinite() && (got - want).norm() <= tolerance * want.norm();
      exact_[(i - 1) * (ny_ - 3) + (j - 1)] = smooth ? 0 : 1;
    }
  }
}

std::size_t FieldLattice::cell_x(double u) const noexcept { return cell_of(u, nx_); }
std::size_t FieldLattice::cell_y(double v) const noexcept { return cell_of(v, ny_); }

Mat2 FieldLattice::interpolate(std::size_t i, std::size_t j, double tx, double ty) const noexcept {
  double wx[4], wy[4];
  catmull_rom(tx, wx);
  catmull_rom(ty, wy);
  // Σ_a wx[a]·Σ_b wy[b]·C(i−1+a, j−1+b) on the four entries as plain doubles (the compiler vectorises it).
  double sum[4] = {0.0, 0.0, 0.0, 0.0};
  for (std::size_t a = 0; a < 4; ++a) {
    const double* row = values_[(i - 1 + a) * ny_ + (j - 1)].data();
    double column[4] = {0.0, 0.0, 0.0, 0.0};
    for (std::size_t b = 0; b < 4; ++b) {
      for (std::size_t e = 0; e < 4; ++e) column[e] += wy[b] * row[4 * b + e];
    }
    for (std::size_t e = 0; e < 4; ++e) sum[e] += wx[a] * column[e];
  }
  Mat2 out;
  out << sum[0], sum[2], sum[1], sum[3];  // Mat2 is stored column by column
  return out;
}

bool FieldLattice::read(const Vec2& p, Mat2& out) const noexcept {
  if (!region_.contains(p)) return false;
  const double u = (p.x() - x0_) * inverse_h_, v = (p.y() - y0_) * inverse_h_;
  const std::size_t i = cell_x(u), j = cell_y(v);
  if (exact_[(i - 1) * (ny_ - 3) + (j - 1)]) return false;
  out = interpolate(i, j, u - static_cast<double>(i), v - static_cast<double>(j));
  return true;
}

bool FieldLattice::covers(const Vec2& p) const noexcept {
  if (!region_.contains(p)) return false;
  const std::size_t i = cell_x((p.x() - x0_) * inverse_h_), j = cell_y((p.y() - y0_) * inverse_h_);
  return exact_[(i - 1) * (ny_ - 3) + (j - 1)] == 0;
}

std::size_t FieldLattice::exact_cells() const noexcept {
  return static_cast<std::size_t>(std::count(exact_.begin(), exact_.end(), std::uint8_t{1}));
}

}  // namespace stiffpath::compliance
