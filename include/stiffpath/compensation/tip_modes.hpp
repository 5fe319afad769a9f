// The compliant tip's modes from a compliance matrix and the moving mass: K^{1/2}, damping, natural frequency.
#pragma once

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/types.hpp"

namespace stiffpath::compensation {

using kinematics::Mat2;
using kinematics::Vec2;

//! The principal square root of a 2×2 matrix with real positive eigenvalues (compliance or
//! stiffness): √A = (A + s·I)/t with s = √det A, t = √(tr A + 2s). Returns the zero matrix when A
//! has no such root (det ≤ 0, tr + 2s ≤ 0 or anything not finite), so that callers never see NaN.
[[nodiscard]] Mat2 matrix_sqrt(const Mat2& A) noexcept;

//! The tip's time-constant matrix T = K⁻¹·D = C·D for the modal damping D = 2ζ√m·K^{1/2}
//! (every eigen-mode of K = C⁻¹ gets the damping ratio ζ): T = 2ζ√m·C^{1/2} (s). In the tip model
//! m·p̈ = −K(p − p_b) − D(ṗ − ṗ_b) the base's offset δ = p_b − p obeys δ + T·δ̇ = C·m·p̈.
//! Zero when C has no real square root.
[[nodiscard]] Mat2 tip_time_constant(const Mat2& C, double mass_kg, double damping_ratio) noexcept;

//! The lowest undamped natural frequency (Hz) of a mass m on the stiffness C⁻¹:
//! f = 1/(2π·√(m·λ_max(C))). 0 when C has no positive real eigenvalue or anything is not finite.
[[nodiscard]] double lowest_natural_frequency_hz(const Mat2& C, double mass_kg) noexcept;

//! The lowest natural frequency (Hz) over a region (clamped into the model's rectangle), from C on a
//! 9 × 9 grid of points: what `--jerk auto` and the shapers' delay bound use. 0 if none is positive.
[[nodiscard]] double lowest_natural_frequency_hz(const compliance::Model& model, double mass_kg,
                                                 const compliance::GridBounds& region) noexcept;

}  // namespace stiffpath::compensation
