// The digital twin's plant and C_true flags shared by `simulate` and `experiment`.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "stiffpath/simulation/simulator.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::cli {

//! What the flags set; `apply` resolves the choices after parsing.
struct TwinFlags {
  std::string truth = "structural";  //!< C_true family
  std::string servo = "loaded";      //!< "loaded" (the drive feels the tip) or "ideal"
  bool no_cg_lever = false;
};

//! Adds --truth, --servo, --motor-inertia-kg-m2, --load-feedforward, --mass-scale, --no-cg-lever,
//! --damping-ratio, --servo-bandwidth-hz and --step-rate-hz.
void add_twin_flags(CLI::App* cmd, TwinFlags& flags, simulation::SimulationOptions& sim,
                    simulation::TrueComplianceOptions& truth);
//! Applies the choices to the options (after parsing).
void apply_twin_flags(const TwinFlags& flags, simulation::SimulationOptions& sim,
                      simulation::TrueComplianceOptions& truth);

}  // namespace stiffpath::cli
