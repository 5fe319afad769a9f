// The twin's C_true sampled on a lattice and read back by Catmull–Rom bicubic interpolation.
#include "stiffpath/simulation/tabulated_field.hpp"

#include <nlohmann/json.hpp>

#include "stiffpath/compliance/model_file.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "stiffpath/core/error.hpp"

namespace stiffpath::simulation {

using compliance::GridBounds;
using compliance::Mat2;
using compliance::Vec2;

namespace {
const compliance::Model& checked(const std::shared_ptr<const compliance::Model>& base) {
  if (!base) throw Error("tabulated field: no base model");
  return *base;
}
}  // namespace

TabulatedModel::TabulatedModel(std::shared_ptr<const compliance::Model> base, const GridBounds& region,
                               double spacing_m)
    : base_(std::move(base)),
      lattice_([model = &checked(base_)](const Vec2& p) { return model->compliance(p); }, region, spacing_m) {
  set_outside_policy(base_->outside_policy());
  set_zero_force(base_->zero_force());
}

Mat2 TabulatedModel::compliance(const Vec2& p) const noexcept {
  Mat2 c;
  return lattice_.read(p, c) ? c : base_->compliance(p);
}

nlohmann::json TabulatedModel::parameters() const {
  nlohmann::json out = compliance::model_parameters(*base_);
  const GridBounds& r = lattice_.region();
  out["tabulated"] = {{"spacing_mm", lattice_.spacing_m() * 1e3},
                      {"x_mm", {r.x_min * 1e3, r.x_max * 1e3}},
                      {"y_mm", {r.y_min * 1e3, r.y_max * 1e3}},
                      {"interpolation", "catmull-rom bicubic"},
                      {"exact_cells", lattice_.exact_cells()}};
  return out;
}

std::shared_ptr<const compliance::Model> tabulate_true_field(std::shared_ptr<const compliance::Model> base) {
  const GridBounds b = base->bounds();
  const double margin = std::max(0.05, 0.25 * std::max(b.x_max - b.x_min, b.y_max - b.y_min));
  return std::make_shared<TabulatedModel>(std::move(base), b.grown(margin), 0.5e-3);
}

}  // namespace stiffpath::simulation
