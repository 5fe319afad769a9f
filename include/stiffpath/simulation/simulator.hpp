// Running a joint trajectory through the plant: interpolated servo references, laser marking, settling.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "stiffpath/compensation/samples.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/simulation/plant.hpp"

namespace stiffpath::simulation {

//! Settings of a simulated job. Documented defaults.
struct SimulationOptions {
  PlantOptions plant;
  double settle_s = 0.10;          //!< time simulated after the last command, holding it (residual vibration)
  double mark_rate_hz = 10000.0;   //!< rate at which the laser's mark is recorded (≤ the step rate)
  //! The CG lever added to C_true for the inertial load (make_cg_lever); null = the CG at G.
  std::shared_ptr<const compliance::Model> cg_lever;
  //! The plant's moving mass relative to the robot's (what the controller and compensation assume): 1.25 =
  //! 25 % heavier than believed.
  double mass_scale = 1.0;
};

//! What a simulated job produced. Points in m.
struct SimulationResult {
  std::vector<Vec2> marked;         //!< tool point while the laser was on, in time order
  std::vector<Vec2> commanded;      //!< planned target points of the laser-on commands
  double duration_s = 0.0;          //!< commanded job time (first to last sample)
  double peak_deflection_m = 0.0;   //!< max |p − p_b| during the job
  double residual_vibration_m = 0.0; //!< max |p − p_b| during the settling time after the last command
  double peak_tracking_error_m = 0.0; //!< max |p_b − FK(q_ref)|: servo error at the base point
  std::uint64_t steps = 0;          //!< integration steps taken
  std::size_t strokes = 0;          //!< laser strokes (maximal runs of laser-on command intervals)
};

//! One laser stroke: a maximal run of command intervals whose starting sample has the laser on.
//! Points in m, in time order; the job's `marked` and `commanded` paths are its strokes concatenated.
struct Stroke {
  std::size_t index = 0;         //!< 0-based, in job order
  double start_s = 0.0;          //!< commanded time of the stroke's first sample
  double end_s = 0.0;            //!< commanded time of its last sample (the one that switches the laser off)
  std::vector<Vec2> marked;      //!< tool point while the laser was on
  std::vector<Vec2> commanded;   //!< planned target points of the stroke's samples
};

//! Receives each stroke as soon as it ends (its vectors are reused afterwards: copy what you keep).
using StrokeSink = std::function<void(const Stroke&)>;

//! Source of joint samples in time order (nullopt at the end), e.g. a JointReader or an in-process job.
using JointSource = std::function<std::optional<compensation::JointCommand>()>;

//! Cubic Hermite reference between two joint samples: q and q̇ match both ends, q̈ is linear in between
//! (the drive's interpolation of a 2 kHz stream). `s` ∈ [0, 1] is the fraction of the interval.
JointReference interpolate(const compensation::JointCommand& a, const compensation::JointCommand& b, double s) noexcept;

//! Simulates the job, handing each laser stroke to `on_stroke` when it ends and keeping no mark in
//! the result (`marked` and `commanded` stay empty): time is linear in the job's length and memory
//! bounded by its longest stroke. The plant starts at rest, undeflected, at the first sample's joints; each command
//! interval is split into ⌈interval·step_rate⌉ equal steps; marks are recorded while the interval's
//! starting sample has the laser on. Throws stiffpath::Error when the source is empty, times do not
//! increase, or the state becomes non-finite.
SimulationResult simulate(const JointSource& source, const kinematics::Robot& robot,
                          std::shared_ptr<const compliance::Model> truth, const SimulationOptions& options,
                          const StrokeSink& on_stroke);

//! The same, keeping the whole mark: `marked` and `commanded` hold every stroke, concatenated (for
//! short jobs: memory grows with the job).
SimulationResult simulate(const JointSource& source, const kinematics::Robot& robot,
                          std::shared_ptr<const compliance::Model> truth, const SimulationOptions& options = {});

}  // namespace stiffpath::simulation
