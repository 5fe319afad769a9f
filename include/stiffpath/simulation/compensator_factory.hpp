// The one place where the twin builds its compensation: which model method and which compensator per variant.
#pragma once

#include <memory>
#include <string>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compensation/reference_filter.hpp"
#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::simulation {

//! Which compensation the twin runs.
enum class CompensationVariant {
  //! The thesis's method (§4.2–4.4): the bilinear grid model (eq. 4.12) and the quasi-static correction
  //! p_cmd = p − C·F.
  thesis_quasi_static,
  //! What `stiffpath run --method auto` does: the model cross-validation favours, dynamic compensation
  //! (the tip's spring–damper inverted, compensation::Method::dynamic) on a reference smoothed over
  //! compensation::kDefaultSmoothing_s.
  default_run,
};

//! "thesis" / "default".
const char* to_string(CompensationVariant variant) noexcept;
//! Parses "thesis" | "default"; throws stiffpath::Error naming the known ones.
CompensationVariant parse_compensation_variant(const std::string& text);

//! The compliance::fit_model method the variant fits to the virtual campaign ("bilinear", "auto").
std::string compensation_fit_method(CompensationVariant variant);

//! A variant's compensation: the compensator and the filters its reference passes first.
struct TwinCompensation {
  std::unique_ptr<compensation::Compensator> compensator;
  compensation::FilterChain filters;  //!< empty for the thesis's variant
};

//! The compensation of `variant` for `robot` with `model`, from `base` (gain, enabled, limit checks,
//! damping ratio) at the command rate `rate_hz`: the thesis's variant keeps `base` as it is, the
//! default sets the dynamic method and the default smoothing, as `stiffpath run` does. A disabled
//! `base` gets no filters (the uncompensated robot follows the plan as it is).
TwinCompensation make_compensation(const kinematics::Robot& robot, std::shared_ptr<const compliance::Model> model,
                                   CompensationVariant variant, compensation::CompensatorOptions base, double rate_hz);

}  // namespace stiffpath::simulation
