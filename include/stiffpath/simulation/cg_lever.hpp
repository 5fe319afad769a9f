// The CG above the measured point: the extra translation of G when the inertial force acts at the CG's height.
#pragma once

#include <memory>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::simulation {

//! The lever term L(p) (m/N) added to C_true when the force acts at the CG, h above G: the force's
//! moment M = (0, 0, h) × F = h·(−Fy, Fx) tilts the platform, and by Maxwell–Betti reciprocity the
//! translation of G under a moment equals the tilt under a force at G (tables 3.4–3.7):
//! ∂δ_i/∂M_j = A_ji with A = ∂(rx, ry)/∂(Fx, Fy). Hence δ = h·[A21 −A11; A22 −A12]·F. A is the
//! per-point fit of the robot's measured tilts (eq. 4.8 on the angle columns), bilinear between points
//! (held at the edge value outside). Right-handed angles are assumed (the thesis does not state its
//! convention; with it, a force along +x tilts the platform about +y, ry > 0, as tables 3.4–3.7 show).
//! nullptr when h = 0 or the robot's table has no tilts at every point (then G_U and G_L cannot differ).
std::shared_ptr<const compliance::Model> make_cg_lever(const kinematics::Robot& robot);

//! C_true + L: the compliance the platform shows under its own inertial load (`lever` may be null). Used as
//! the oracle compensation model of the error budget (no model error left).
std::shared_ptr<const compliance::Model> make_loaded_compliance(std::shared_ptr<const compliance::Model> truth,
                                                                std::shared_ptr<const compliance::Model> lever);

}  // namespace stiffpath::simulation
