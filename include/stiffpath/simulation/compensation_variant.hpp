// The compensations the twin compares (without, the thesis's, the default) as job::JobSpecs, one place for all.
#pragma once

#include <cstdint>
#include <optional>

#include "stiffpath/core/enum_names.hpp"
#include "stiffpath/job/job_spec.hpp"

namespace stiffpath::simulation {

//! Which compensation a twin run uses.
enum class CompensationVariant : std::uint8_t {
  without,      //!< none: the planned path as it is (job::JobSpec::compensate = false)
  thesis,       //!< the thesis's method (job::thesis_job): bilinear model, quasi-static, no filter
  default_run,  //!< what `stiffpath run` does by default (job::default_job)
};

//! The job a variant runs on `robot`: job::default_job or job::thesis_job, without compensation for `without`.
job::JobSpec variant_job(const kinematics::Robot& robot, CompensationVariant variant);

//! The fit method of the variant's model on a virtual campaign: bilinear for the thesis's; unset for the
//! others (the robot file's method, else the one cross-validation favours, as `run` fits its table).
std::optional<compliance::FitMethod> compensation_fit_method(CompensationVariant variant);

}  // namespace stiffpath::simulation

//! Names at the edges (results files, --variants): "without", "thesis", "default".
template <>
struct stiffpath::core::EnumNames<stiffpath::simulation::CompensationVariant> {
  static constexpr std::string_view what = "compensation variant";
  static constexpr std::array<std::pair<simulation::CompensationVariant, std::string_view>, 3> names{
      {{simulation::CompensationVariant::without, "without"},
       {simulation::CompensationVariant::thesis, "thesis"},
       {simulation::CompensationVariant::default_run, "default"}}};
};
