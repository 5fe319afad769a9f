// The one place where the twin builds its compensation: which model method and which compensator per variant.
#pragma once

#include <memory>
#include <string>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::simulation {

//! Which compensation the twin runs.
enum class CompensationVariant {
  //! The thesis's method (§4.2–4.4): the bilinear grid model (eq. 4.12) and the quasi-static correction
  //! p_cmd = p − C·F.
  thesis_quasi_static,
  //! What `stiffpath run` does by default: the model its cross-validation favours, and the compensator's
  //! default options.
  default_run,
};

//! "thesis" / "default".
const char* to_string(CompensationVariant variant) noexcept;
//! Parses "thesis" | "default"; throws stiffpath::Error naming the known ones.
CompensationVariant parse_compensation_variant(const std::string& text);

//! The compliance::fit_model method the variant fits to the virtual campaign ("bilinear", "auto").
std::string compensation_fit_method(CompensationVariant variant);

//! The compensator of `variant` for `robot` with `model`, from `base` (gain, enabled, limit checks).
std::unique_ptr<compensation::Compensator> make_compensator(const kinematics::Robot& robot,
                                                            std::shared_ptr<const compliance::Model> model,
                                                            CompensationVariant variant,
                                                            compensation::CompensatorOptions base = {});

}  // namespace stiffpath::simulation
