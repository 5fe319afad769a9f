// libFuzzer harness: the C interface's model loader (stiffpath_compensator_create with a model file for oc-gu), then steps.
#include <cmath>
#include <cstdlib>

#include "fuzz_input.hpp"
#include "stiffpath/stiffpath.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = stiffpath::fuzz::as_file(data, size, "-model.json");
  char error[512];
  stiffpath_options options = stiffpath_default_options();
  options.outside_policy = STIFFPATH_OUTSIDE_CLAMP;  // every point served, so every step reaches the model
  stiffpath_compensator* c = stiffpath_compensator_create("oc-gu", path.c_str(), &options, error, sizeof error);
  if (c == nullptr) {
    if (error[0] == '\0') std::abort();  // a refusal always says why
    return 0;
  }
  // A model that loads serves: a few samples across the thesis robot's region, at 5 g, give finite commands
  // or a status, never NaN with "ok".
  for (int k = 0; k < 9; ++k) {
    stiffpath_task_sample s{};
    s.t_s = 1e-3 * k;
    s.p_m[0] = 0.172 + 0.0125 * k;
    s.p_m[1] = -0.075 + 0.01875 * k;
    s.a_m_s2[0] = 49.0;
    s.a_m_s2[1] = -24.5;
    stiffpath_joint_command out;
    const int status = stiffpath_compensator_step(c, &s, &out);
    if (status == STIFFPATH_OK && !(std::isfinite(out.q_rad[0]) && std::isfinite(out.q_rad[1]))) std::abort();
  }
  stiffpath_compensator_free(c);
  return 0;
}
