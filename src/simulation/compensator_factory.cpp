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

TwinCompensation make_compensation(const kinematics::Robot& robot, std::shared_ptr<const compliance::Model> model,
                                   CompensationVariant variant, compensation::CompensatorOptions base, double rate_hz) {
  TwinCompensation out;
  if (variant == CompensationVariant::default_run && base.enabled) {
    base.method = compensation::Method::dynamic;
    out.filters = compensation::FilterChain(compensation::smoothing_filters(rate_hz, compensation::kDefaultSmoothing_s));
  }
  out.compensator = std::make_unique<compensation::Compensator>(robot, std::move(model), base);
  return out;
}

}  // namespace stiffpath::simulation
