// Floors of the thesis's translation tables: how well any model of a given class can reproduce them.
#pragma once

#include <string>
#include <vector>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::simulation::testing {

//! One table cell's misfit under a floor: which point, load direction ("+x", "-y") and axis (0: dx, 1: dy).
struct FloorCell {
  std::string point, direction;
  int axis = 0;
  double force_N = 0, error_m = 0;
};

struct Floor {
  std::vector<FloorCell> cells;
  [[nodiscard]] int within(double bound_m) const;
  [[nodiscard]] double rms_m() const;
  [[nodiscard]] double max_m() const;
};

//! (b) Every linear model: a straight line (slope and offset, eq. 4.8) per load series — at each point a full,
//! non-symmetric 2×2 compliance.
Floor per_series_floor(const measurement::DisplacementTable& table);

//! (a) Every reciprocal linear elastic model (Maxwell–Betti: C = Cᵀ): at each point the best symmetric 2×2
//! compliance (3 numbers) with each load series' offset.
Floor symmetric_floor(const measurement::DisplacementTable& table);

//! (c) Every structure whose elastic elements all ride on the arms (any actuator, link, joint compliance, any
//! values) plus a constant base translation: with both actuators at the origin such a structure is invariant
//! under rotation about it, C(p) = B + R(φ)·C_l(r)·R(φ)ᵀ, so the mirror points x_i y_j and x_i y_(6−j) (same r)
//! share C_l. Linear least squares over B, one free C_l per radius and the series offsets (no definiteness
//! imposed: a floor).
Floor rotation_invariant_floor(const measurement::DisplacementTable& table);

//! One given model's misfit C·F − d on every cell, each load series with its own offset (the fits' measure).
Floor model_misfit(const compliance::Model& model, const measurement::DisplacementTable& table);

}  // namespace stiffpath::simulation::testing
