// Parsing of the twin's flags: C_true family, loaded or ideal servo, drive inertia, mass error, CG lever.
#include "twin_flags.hpp"
#include "bounded.hpp"

namespace stiffpath::cli {

void add_twin_flags(CLI::App* cmd, TwinFlags& f, simulation::SimulationOptions& sim,
                    simulation::TrueComplianceOptions& truth) {
  cmd->add_option("--truth", f.truth, "C_true: structural (virtual joints) or physical (U^-T D U^-1)")
      ->check(CLI::IsMember({"structural", "physical"}))->capture_default_str();
  cmd->add_option("--perturbation", truth.perturbation, "Relative perturbation of C_true")
      ->check(within(0.0, 0.5, ""))->capture_default_str();
  cmd->add_option("--servo", f.servo, "loaded: the drives feel the tip through J^T; ideal: they track unloaded")
      ->check(CLI::IsMember({"loaded", "ideal"}))->capture_default_str();
  cmd->add_option("--motor-inertia-kg-m2", sim.plant.motor_inertia_kg_m2,
                  "Motor + reducer + proximal link inertia at each joint")
      ->check(within(1e-5, 10.0, ""))->capture_default_str();
  cmd->add_option("--load-feedforward", sim.plant.load_feedforward,
                  "Fraction of the rigid-body torque feed-forward of the platform mass")
      ->check(within(0.0, 2.0, ""))->capture_default_str();
  cmd->add_option("--load-feedforward-from", f.feedforward_from,
                  "reference: the rigid-body model at the joint commands; command: the job's D'Alembert force (fx_n, fy_n)")
      ->check(CLI::IsMember({"reference", "command"}))->capture_default_str();
  cmd->add_option("--mass-scale", sim.mass_scale, "Plant mass / the mass the controller and compensation assume")
      ->check(within(0.1, 5.0, ""))->capture_default_str();
  cmd->add_flag("--no-cg-lever", f.no_cg_lever, "Put the CG at the measured point (no platform tilt)");
  cmd->add_option("--damping-ratio", sim.plant.tip_damping_ratio,
                  "Damping ratio of the tip's modes (default: the robot file's tip_damping_ratio, 0.05 when it gives none)")
      ->check(within(0.0, 2.0, ""));
  cmd->add_option("--servo-bandwidth-hz", sim.plant.servo_bandwidth_hz, "Joint position-loop bandwidth")
      ->check(within(1.0, 2000.0, ""))->capture_default_str();
  cmd->add_option("--step-rate-hz", sim.plant.step_rate_hz, "Integration rate")
      ->check(within(1000.0, 1e7, ""))->capture_default_str();
}

void apply_twin_flags(const TwinFlags& f, simulation::SimulationOptions& sim, simulation::TrueComplianceOptions& truth) {
  truth.family = core::parse_enum<simulation::TrueFamily>(f.truth);
  sim.plant.servo_feels_load = f.servo == "loaded";
  sim.plant.load_feedforward_from_command = f.feedforward_from == "command";
}

}  // namespace stiffpath::cli
