// motion_along: the point's rates from the arc length's rates on a line or an arc (chain rule, constant curvature).
#include "stiffpath/compensation/path_motion.hpp"

namespace stiffpath::compensation {

std::array<Vec2, 6> motion_along(const PathGeometry& g, const std::array<double, 6>& sigma) noexcept {
  const double s1 = sigma[1], s2 = sigma[2], s3 = sigma[3], s4 = sigma[4], s5 = sigma[5];
  const double k = g.curvature_1_m, k2 = k * k;
  const Vec2 T = g.tangent, N(-T.y(), T.x());
  const double s1_2 = s1 * s1, s1_3 = s1_2 * s1;
  return {g.position_m,
          s1 * T,
          s2 * T + (k * s1_2) * N,
          (s3 - k2 * s1_3) * T + (3.0 * k * s1 * s2) * N,
          (s4 - 6.0 * k2 * s1_2 * s2) * T + (k * (4.0 * s1 * s3 + 3.0 * s2 * s2 - k2 * s1_2 * s1_2)) * N,
          (s5 - 15.0 * k2 * s1 * s2 * s2 - 10.0 * k2 * s1_2 * s3 + k2 * k2 * s1_3 * s1_2) * T +
              (k * (10.0 * s2 * s3 + 5.0 * s1 * s4 - 10.0 * k2 * s1_3 * s2)) * N};
}

}  // namespace stiffpath::compensation
