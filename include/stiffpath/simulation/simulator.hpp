// Running a joint trajectory through the plant: interpolated servo references, laser marking, settling.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "stiffpath/compensation/samples.hpp"
#include "stiffpath/core/error.hpp"
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
  //! Work budget: the most integration steps a job may take (its motion and the settling). A source
  //! that asks for more is refused (RecordRefused) at the record that would exceed it, before that
  //! interval is stepped. 3·10⁸: 4 h 10 min of motion at the default 20 kHz (about 50 s of CPU).
  std::uint64_t max_steps = 300'000'000;
};

//! A record of the joint source that the twin refuses: a command beyond the robot's joint limits or
//! reach, or one that would take the job beyond SimulationOptions::max_steps. Callers that know where
//! the records come from (a file) name the place.
class RecordRefused : public Error {
 public:
  RecordRefused(std::size_t record, const std::string& message);
  //! 0-based index of the record in the source.
  [[nodiscard]] std::size_t record() const noexcept { return record_; }

 private:
  std::size_t record_;
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
  //! For each point of `commanded`, the index in `marked` of the first mark recorded after it (the
  //! marks of the interval it starts; Stroke::first_mark, strokes concatenated).
  std::vector<std::size_t> first_mark;
};

//! One laser stroke: a maximal run of command intervals whose starting sample has the laser on.
//! Points in m, in time order; the job's `marked` and `commanded` paths are its strokes concatenated.
struct Stroke {
  std::size_t index = 0;         //!< 0-based, in job order
  double start_s = 0.0;          //!< commanded time of the stroke's first sample
  double end_s = 0.0;            //!< commanded time of its last sample (the one that switches the laser off)
  std::vector<Vec2> marked;      //!< tool point while the laser was on
  std::vector<Vec2> commanded;   //!< planned target points of the stroke's samples
  //! For each commanded point k, the index in `marked` of the first mark recorded after it: the marks
  //! of the interval that sample k starts are marked[first_mark[k] … first_mark[k + 1]).
  std::vector<std::size_t> first_mark;
};

//! Receives each stroke as soon as it ends (its vectors are reused afterwards: copy what you keep).
using StrokeSink = std::function<void(const Stroke&)>;

//! Receives the laser's strokes while they are marked, so that nothing of a stroke need be kept: for
//! each stroke begin_stroke(), then its command samples in time order, each followed by the marks
//! recorded in the interval it starts (the job's first sample is followed by the tip's point at the
//! start when the laser is on from the start), the last command (the sample that switches the laser off,
//! or the job's last) and end_stroke().
class StrokeObserver {
 public:
  virtual ~StrokeObserver() = default;
  //! A stroke starts; `index` counts the job's strokes from 0, `t_s` is its first sample's time.
  virtual void begin_stroke(std::size_t index, double t_s) = 0;
  //! The next command sample of the stroke: its planned target point (m).
  virtual void command(const Vec2& target_m) = 0;
  //! A mark: the tool point recorded while the laser is on (m).
  virtual void mark(const Vec2& tip_m) = 0;
  //! The stroke has ended; `t_s` is its last sample's time.
  virtual void end_stroke(double t_s) = 0;
};

//! Source of joint samples in time order (nullopt at the end), e.g. a JointReader or an in-process job.
using JointSource = std::function<std::optional<compensation::JointCommand>()>;

//! Cubic Hermite reference between two joint samples: q and q̇ match both ends, q̈ is linear in between
//! (the drive's interpolation of a 2 kHz stream). `s` ∈ [0, 1] is the fraction of the interval.
JointReference interpolate(const compensation::JointCommand& a, const compensation::JointCommand& b, double s) noexcept;

//! Simulates the job, handing its strokes to `observer` as they are marked and keeping no mark in the
//! result (`marked` and `commanded` stay empty): time is linear in the job's length and the memory
//! the observer's. The plant starts at rest, undeflected, at the first sample's joints; each command
//! interval is split into ⌈interval·step_rate⌉ equal steps; marks are recorded while the interval's
//! starting sample has the laser on. Every record is checked where it enters: its joints within the
//! robot's limits, a tip the robot reaches in its own working mode (not through a singularity), and
//! the steps it asks for within max_steps; else RecordRefused. Throws stiffpath::Error when the source
//! is empty, times do not increase, or the state becomes non-finite.
SimulationResult simulate(const JointSource& source, const kinematics::Robot& robot,
                          std::shared_ptr<const compliance::Model> truth, const SimulationOptions& options,
                          StrokeObserver& observer);

//! The same, handing each laser stroke whole to `on_stroke` when it ends (memory grows with the
//! longest stroke: for short jobs, plots and tests).
SimulationResult simulate(const JointSource& source, const kinematics::Robot& robot,
                          std::shared_ptr<const compliance::Model> truth, const SimulationOptions& options,
                          const StrokeSink& on_stroke);

//! The same, keeping the whole mark: `marked` and `commanded` hold every stroke, concatenated (for
//! short jobs: memory grows with the job).
SimulationResult simulate(const JointSource& source, const kinematics::Robot& robot,
                          std::shared_ptr<const compliance::Model> truth, const SimulationOptions& options = {});

}  // namespace stiffpath::simulation
