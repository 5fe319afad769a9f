// Benchmark helper: a long Lissajous marking motion over the thesis's workspace as compensation input samples.
#pragma once

#include <cmath>
#include <vector>

#include "stiffpath/compensation/samples.hpp"

namespace stiffpath::bench {

// One hour would be 7.2 M samples; 400 000 samples (200 s at 2 kHz) keep the run short.
inline std::vector<compensation::TaskSample> job_samples() {
  std::vector<compensation::TaskSample> out;
  const double w = 2 * M_PI * 2.0;
  for (int k = 0; k < 400000; ++k) {
    const double t = k / 2000.0;
    compensation::TaskSample s;
    s.t_s = t;
    s.position_m = {0.222 + 0.045 * std::sin(w * t), 0.07 * std::sin(2 * w * t)};
    s.velocity_m_s = {0.045 * w * std::cos(w * t), 0.14 * w * std::cos(2 * w * t)};
    s.acceleration_m_s2 = {-0.045 * w * w * std::sin(w * t), -0.28 * w * w * std::sin(2 * w * t)};
    s.jerk_m_s3 = {-0.045 * w * w * w * std::cos(w * t), -0.56 * w * w * w * std::cos(2 * w * t)};
    out.push_back(s);
  }
  return out;
}

}  // namespace stiffpath::bench
