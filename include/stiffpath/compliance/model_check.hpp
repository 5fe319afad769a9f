// The physics every compliance model must obey where it serves: finite, bounded, and positive definite.
#pragma once

#include <optional>
#include <string>

#include "stiffpath/compliance/model.hpp"

namespace stiffpath::compliance {

//! Largest compliance entry a model may hold (1000 µm/N = 1 mm/N, in m/N): about 10³ times the thesis
//! robots' (0.5–2.5 µm/N), so any real robot passes and 1e300 does not.
inline constexpr double max_compliance_m_per_N = 1e-3;

//! Where a model breaks physics: the point, its compliance there, and why.
struct ModelDefect {
  Vec2 point_m;
  Mat2 compliance_m_per_N;
  std::string word;    //!< "RANGE" (not finite, beyond the bound) or "PHYSICS" (not positive definite)
  std::string reason;  //!< "beyond ±1000 um/N", "not positive definite (…)"
  //! "WORD: the model's compliance at (x, y) mm is [a b; c d] um/N, " + reason
  [[nodiscard]] std::string describe() const;
};

//! Checks a model at every point it serves (its measured rectangle grown by kOutsideMargin_m, where
//! the clamp and error policies serve it; beyond, the policies clamp): on a 41 × 41 lattice, plus
//! every node of a grid model, C(p) must be finite, within ±max_compliance_m_per_N, and positive
//! definite: FᵀC(p)F > 0 for every force F, i.e. its symmetric part (C + Cᵀ)/2 positive definite
//! (a load does work on the platform, never the reverse; measured compliances are not exactly
//! symmetric, so the symmetric part is what is required). Returns the first defect, or nothing.
[[nodiscard]] std::optional<ModelDefect> find_model_defect(const Model& model);

}  // namespace stiffpath::compliance
