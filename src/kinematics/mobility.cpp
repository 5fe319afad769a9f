// Grübler–Kutzbach mobility criterion, thesis eqs. 3.1–3.2.
#include "stiffpath/kinematics/mobility.hpp"

#include <numeric>

#include "stiffpath/core/error.hpp"

namespace stiffpath::kinematics {

int gruebler_kutzbach(const Linkage& linkage) {
  if (linkage.space_dof != 3 && linkage.space_dof != 6) {
    throw Error("linkage '" + linkage.name + "': space DoF must be 3 or 6, got " + std::to_string(linkage.space_dof));
  }
  if (linkage.links < 1) throw Error("linkage '" + linkage.name + "': needs at least the ground link");
  for (const int f : linkage.joint_freedoms) {
    if (f < 1 || f >= linkage.space_dof) {
      throw Error("linkage '" + linkage.name + "': joint freedom " + std::to_string(f) + " outside [1, " +
                  std::to_string(linkage.space_dof - 1) + "]");
    }
  }
  const int joints = static_cast<int>(linkage.joint_freedoms.size());
  const int freedoms = std::accumulate(linkage.joint_freedoms.begin(), linkage.joint_freedoms.end(), 0);
  return linkage.space_dof * (linkage.links - joints - 1) + freedoms;
}

int actual_mobility(const Linkage& linkage) {
  if (linkage.redundant_constraints < 0) throw Error("linkage '" + linkage.name + "': negative redundant constraints");
  return gruebler_kutzbach(linkage) + linkage.redundant_constraints;
}

std::vector<Linkage> thesis_linkages() {
  return {
      {"6R planar", 3, 6, std::vector<int>(6, 1), 0,
       "a single closed 6R loop: 2 translations and 1 rotation of the platform"},
      {"simply-constrained 6R (SC)", 3, 11, std::vector<int>(14, 1), 0,
       "the parallelogram loops keep the platform's orientation: it only translates in x and y"},
      {"over-constrained 6R (OC)", 3, 12, std::vector<int>(16, 1), 1,
       "the extra link closes a parallelogram whose sides are parallel and equal, so its loop "
       "constraint repeats one that the other loops already impose; eq. 3.1 counts it twice and "
       "reports 1, but the linkage moves with 2 DoF like SC"},
  };
}

}  // namespace stiffpath::kinematics
