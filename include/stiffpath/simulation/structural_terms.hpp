// A known compliance field written in the robot's own terms (its actuators', links' and base's compliances), for rehearsals.
#pragma once

#include <memory>
#include <string>

#include "stiffpath/simulation/structural_compliance.hpp"

namespace stiffpath::simulation {

//! The structural model of `robot` whose elements are given as text: comma-separated `name=value` terms, a value
//! for both arms or `left/right`, SI units in the names:
//!   actuator_rad_per_Nm, proximal_bending_per_Nm2, proximal_axial_m_per_N, distal_axial_m_per_N (per arm),
//!   base_x_m_per_N, base_y_m_per_N, base_rotation_rad_per_Nm (the frame).
//! E.g. "actuator_rad_per_Nm=2e-5/3e-5,distal_axial_m_per_N=5e-8,base_x_m_per_N=1e-8". Elements not named are
//! rigid; the parallelogram bars carry nothing (pin-ended distal links: the classic C = J·K⁻¹·Jᵀ plus the links).
//! Each value must be finite, ≥ 0 and ≤ 1 (SI); throws stiffpath::Error naming the term otherwise, or for an
//! unknown name (listing the known ones). `region`: the model's rectangle (bounds()).
std::shared_ptr<StructuralModel> structural_model_from_terms(const kinematics::Robot& robot, const std::string& terms,
                                                             const compliance::GridBounds& region);

}  // namespace stiffpath::simulation
