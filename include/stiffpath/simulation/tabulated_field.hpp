// A smooth compliance field sampled once on a fine lattice and read back by bicubic interpolation: the twin's C_true at table speed.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <memory>

#include "stiffpath/compliance/field_lattice.hpp"
#include "stiffpath/compliance/model.hpp"

namespace stiffpath::simulation {

//! `base` sampled on a square lattice of `spacing_m` over `region` (plus one node of stencil beyond
//! it on every side), evaluated by Catmull–Rom bicubic interpolation of the lattice: C¹, exact for
//! fields linear in x and y, error O(h³·|∂³C|). Every cell is checked at its centre when the table is
//! made; a cell that reads more than 10⁻⁶ (relative) off there, and every point outside `region`, is
//! evaluated by `base` itself, so the field is unchanged wherever the lattice cannot follow it. For fields that are expensive to evaluate and
//! smooth on the lattice's scale — the structural C_true, an inverse kinematics and a network of
//! arms per point — which the twin evaluates at every 20 kHz step.
//! `base` must be thread-safe to read; the table is filled in the constructor and only read after.
class TabulatedModel final : public compliance::Model {
 public:
  TabulatedModel(std::shared_ptr<const compliance::Model> base, const compliance::GridBounds& region, double spacing_m);

  [[nodiscard]] std::optional<compliance::FitMethod> method() const noexcept override { return base_->method(); }
  [[nodiscard]] std::string description() const override { return base_->description(); }
  [[nodiscard]] compliance::Mat2 compliance(const compliance::Vec2& p) const noexcept override;
  [[nodiscard]] compliance::GridBounds bounds() const noexcept override { return base_->bounds(); }
  //! The base's parameters, with the lattice's spacing and region.
  //! Its parameters and fit statistics as JSON, as model files hold them (compliance::model_parameters).
  [[nodiscard]] nlohmann::json parameters() const;

  [[nodiscard]] const compliance::GridBounds& region() const noexcept { return lattice_.region(); }
  [[nodiscard]] double spacing_m() const noexcept { return lattice_.spacing_m(); }
  [[nodiscard]] std::size_t nodes() const noexcept { return lattice_.nodes(); }
  //! Cells left to the base (not smooth enough on the lattice's scale).
  [[nodiscard]] std::size_t exact_cells() const noexcept { return lattice_.exact_cells(); }
  //! Whether compliance(p) reads the lattice (false: it asks the base).
  [[nodiscard]] bool reads_lattice(const compliance::Vec2& p) const noexcept { return lattice_.covers(p); }

 private:
  std::shared_ptr<const compliance::Model> base_;
  compliance::FieldLattice lattice_;
};

//! C_true's default lattice: 0.5 mm over the measured rectangle grown by max(50 mm, its larger side / 4).
std::shared_ptr<const compliance::Model> tabulate_true_field(std::shared_ptr<const compliance::Model> base);

}  // namespace stiffpath::simulation
