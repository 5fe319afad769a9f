// Grübler–Kutzbach mobility (thesis eq. 3.1) and the thesis's three 6R linkages (eq. 3.2).
#pragma once

#include <string>
#include <vector>

namespace stiffpath::kinematics {

//! A linkage described by counts, as eq. 3.1 needs it.
struct Linkage {
  std::string name;
  int space_dof = 3;                  //!< λ: 3 for planar/spherical, 6 for spatial
  int links = 0;                      //!< L, including the ground link
  std::vector<int> joint_freedoms;    //!< f_k of each joint (J = size)
  int redundant_constraints = 0;      //!< constraints that duplicate others (special geometry)
  std::string note;                   //!< why the real mobility differs, when it does
};

//! Eq. 3.1: M = λ(L − J − 1) + Σ f_k. Throws stiffpath::Error for λ ∉ {3, 6}, L < 1 or f_k ∉ [1, λ−1].
int gruebler_kutzbach(const Linkage& linkage);
//! Real mobility = eq. 3.1 + redundant constraints (an over-constrained linkage moves more than
//! eq. 3.1 says because some of its loop constraints are linearly dependent).
int actual_mobility(const Linkage& linkage);

//! Eq. 3.2's three cases: plain 6R (M = 3), simply-constrained 6R (M = 2), over-constrained 6R (M = 1,
//! moving with 2 DoF).
std::vector<Linkage> thesis_linkages();

}  // namespace stiffpath::kinematics
