// Compensator construction per variant, kept in one function so new compensation options land in one place.
#include "stiffpath/simulation/compensator_factory.hpp"

#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::simulation {

const char* to_string(CompensationVariant variant) noexcept {
  return variant == CompensationVariant::thesis_quasi_static ? "thesis" : "default";
}

CompensationVariant parse_compensation_variant(const std::string& text) {
  if (text == "thesis") return CompensationVariant::thesis_quasi_static;
  if (text == "default") return CompensationVariant::default_run;
  throw Error(fmt::format("unknown compensation variant '{}' (known: thesis, default)", text));
}

std::string compensation_fit_method(CompensationVariant variant) {
  return variant == CompensationVariant::thesis_quasi_static ? "bilinear" : "auto";
}

std::unique_ptr<compensation::Compensator> make_compensator(const kinematics::Robot& robot,
                                                            std::shared_ptr<const compliance::Model> model,
                                                            CompensationVariant variant,
                                                            compensation::CompensatorOptions base) {
  // Both variants use the quasi-static step today; the default's further options (dynamic inversion,
  // smooth commands) are set here once the compensation module offers them.
  (void)variant;
  return std::make_unique<compensation::Compensator>(robot, std::move(model), base);
}

}  // namespace stiffpath::simulation
