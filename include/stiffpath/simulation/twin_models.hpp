// The digital twin's two compliances: the plant's true field C_true and the compensation model fitted to a virtual campaign on it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::simulation {

//! The family of the twin's true compliance field.
enum class TrueFamily : std::uint8_t {
  structural,  //!< simulation::StructuralModel: virtual joints, of a family no compensation model has
  physical,    //!< order 1, C = U⁻ᵀ D(p) U⁻¹: the family of the compensation's `physical` fit
};

//! How C_true is made. Defaults: the structural model fitted to the robot's own data, perturbed by ±10 %.
struct TrueComplianceOptions {
  //! Base field: a built-in or file model (compliance::load_model); empty = `family` fitted to all of the
  //! robot's table, or the robot's model file when it names no table.
  std::string base_model;
  //! Relative amplitude ε of the seeded smooth perturbation: C_true = S C S, S = diag(√sx, √sy), sx and sy
  //! quadratic polynomials over the grid with values in [1 − ε, 1 + ε]. Keeps C_true symmetric positive
  //! definite and makes it differ from anything the thesis's data say. 0 = the base field itself.
  double perturbation = 0.10;
  std::uint64_t seed = 1;  //!< seed of the perturbation's coefficients
  TrueFamily family = TrueFamily::structural;
  //! An already made base field (e.g. one structural fit shared by many seeds); overrides the above.
  std::shared_ptr<const compliance::Model> base;
};

//! The true compliance of `robot` (m/N). Throws stiffpath::Error when the robot has no compliance data,
//! for a bad base model (or one fitted for another geometry) or ε outside [0, 0.5].
std::shared_ptr<const compliance::Model> make_true_compliance(const kinematics::Robot& robot,
                                                              const TrueComplianceOptions& options = {});
//! The unperturbed base field of make_true_compliance (extrapolating beyond the measured rectangle).
std::shared_ptr<const compliance::Model> make_true_base(const kinematics::Robot& robot,
                                                        const TrueComplianceOptions& options = {});

//! How the compensation model is obtained from C_true (the thesis's route, §2.3 and §4.2).
struct CampaignFitOptions {
  //! The fit's method; unset: the robot file's, else the one cross-validation of the virtual table favours.
  std::optional<compliance::FitMethod> method;
  double noise_sigma_m = 11.5e-6;   //!< σ per CMM coordinate: the arm's ±23 µm as a 2σ bound
  std::uint64_t seed = 7;           //!< seed of the campaign's noise
};

//! The displacement table a campaign on `truth` would measure: the robot's own measurement points,
//! directions, load steps and forces (its table), dx, dy = C_true(p)·F (F = F_N along the load
//! direction), dz and the tilts from its data's own linear trend (zero when the table has none), then
//! CMM readings with noise (measurement::simulate_campaign, with the robot's replica, or G read
//! directly when it has none) and processing by eq. 2.3 (measurement::process_campaign).
measurement::DisplacementTable virtual_campaign_table(const compliance::Model& truth, const kinematics::Robot& robot,
                                                      const CampaignFitOptions& options = {});

//! The model the compensation uses: `options.method` fitted to virtual_campaign_table (no inverse crime:
//! the fit never sees C_true itself, only noisy readings at the measured points).
std::shared_ptr<const compliance::Model> fit_compensation_model(const compliance::Model& truth,
                                                                const kinematics::Robot& robot,
                                                                const CampaignFitOptions& options = {});

}  // namespace stiffpath::simulation

//! Names at the edges (--truth): "structural", "physical".
template <>
struct stiffpath::core::EnumNames<stiffpath::simulation::TrueFamily> {
  static constexpr std::string_view what = "C_true family";
  static constexpr std::array<std::pair<simulation::TrueFamily, std::string_view>, 2> names{
      {{simulation::TrueFamily::structural, "structural"}, {simulation::TrueFamily::physical, "physical"}}};
};
