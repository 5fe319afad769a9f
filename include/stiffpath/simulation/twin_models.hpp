// The digital twin's two compliances: the plant's true field C_true and the compensation model fitted to a virtual campaign on it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::simulation {

//! How C_true is made. Defaults: the physics-based model fitted to the thesis's data, perturbed by ±10 %.
struct TrueComplianceOptions {
  //! Base field: a built-in or file model (compliance::load_model); empty = "thesis-<build>-physical",
  //! the smooth, symmetric, positive definite C = U⁻ᵀ D(p) U⁻¹ fitted to all of the thesis's data.
  std::string base_model;
  //! Relative amplitude ε of the seeded smooth perturbation: C_true = S C S, S = diag(√sx, √sy), sx and sy
  //! quadratic polynomials over the grid with values in [1 − ε, 1 + ε]. Keeps C_true symmetric positive
  //! definite and makes it differ from anything the thesis's data say. 0 = the base field itself.
  double perturbation = 0.10;
  std::uint64_t seed = 1;  //!< seed of the perturbation's coefficients
};

//! The true compliance of build "OC" or "SC" (m/N). Throws stiffpath::Error for an unknown build,
//! a bad base model or ε outside [0, 0.5].
std::shared_ptr<const compliance::Model> make_true_compliance(const std::string& build,
                                                              const TrueComplianceOptions& options = {});

//! How the compensation model is obtained from C_true (the thesis's route, §2.3 and §4.2).
struct CampaignFitOptions {
  std::string method = "bilinear";  //!< compliance::fit_model method; the thesis's grid + eq. 4.12
  double noise_sigma_m = 11.5e-6;   //!< σ per CMM coordinate: the arm's ±23 µm as a 2σ bound
  std::uint64_t seed = 7;           //!< seed of the campaign's noise
};

//! The displacement table a campaign on `truth` would measure: the thesis's 15 points, directions and
//! 5 load steps, dx, dy = C_true(p)·F (F = F_N along the load direction), dz and the tilts from the
//! thesis data's own linear trend, then CMM readings with noise (measurement::simulate_campaign) and
//! processing by eq. 2.3 (measurement::process_campaign).
measurement::DisplacementTable virtual_campaign_table(const compliance::Model& truth, const std::string& build,
                                                      const CampaignFitOptions& options = {});

//! The model the compensation uses: `options.method` fitted to virtual_campaign_table (no inverse crime:
//! the fit never sees C_true itself, only noisy readings at 15 points).
std::shared_ptr<const compliance::Model> fit_compensation_model(const compliance::Model& truth, const std::string& build,
                                                                const CampaignFitOptions& options = {});

}  // namespace stiffpath::simulation
