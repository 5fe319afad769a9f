// The main job as one typed value: robot, compliance model, compensation, reference filters, planning and output.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compensation/reference_filter.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/job/task_source.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::job {

//! Which compliance model compensates the job. Default: the robot's own (its model file, else its table
//! fitted with the method its file names, else with the one cross-validation favours).
struct ModelChoice {
  compliance::ModelRequest request;  //!< a model file or built-in name, a refit of the robot's table, …
  //! A model already in memory (the twin's fitted model, a binding's Model); overrides `request`.
  std::shared_ptr<const compliance::Model> given;
  std::string given_label = "the given model";  //!< how messages name `given`
};

//! How the jerk limit of the plan is chosen.
enum class JerkRule : std::uint8_t {
  planned,        //!< plan.limits.max_jerk_m_s3 as it is (motion's default: the acceleration over 5 ms)
  tip_frequency,  //!< the acceleration limit times the tip's lowest natural frequency over the job's region
};

//! The cap on the samples a job may write (20 M: 2 h 46 min 40 s at 2 kHz); raise it per job.
inline constexpr std::uint64_t kDefaultMaxSamples = 20'000'000;
//! The most samples any job may plan and compensate, written or not (10⁹: 138 h at 2 kHz, minutes of work).
inline constexpr std::uint64_t kMaxJobSamples = 1'000'000'000;

//! Everything that decides a compensated job's joint commands, with one set of documented defaults for
//! every surface (CLI, C, Python, MATLAB, the twin). SI units throughout.
//!
//! "Without compensation" (`compensate = false`) is one thing everywhere: the planned path converted to
//! joint angles as it is (p_cmd = p), with no reference filter unless one is asked for by name.
struct JobSpec {
  kinematics::Robot robot;  //!< the robot (kinematics::load_robot); its numbers come from its own file
  ModelChoice model;

  bool compensate = true;  //!< false: without compensation (see above)
  compensation::Method method = compensation::Method::dynamic;  //!< the tip's damped dynamics inverted
  double gain = 1.0;                                            //!< k in p_cmd = p − k·Δ, 0 … 10
  std::optional<double> damping_ratio;  //!< ζ of the tip's modes, 0 … 0.9; unset: the robot's tip_damping_ratio
  std::optional<compliance::OutsidePolicy> outside;  //!< unset: the model's own policy (error unless fitted otherwise)
  AccelerationSource acceleration = AccelerationSource::analytic;
  bool check_limits = true;  //!< reach and joint limits on every sample

  //! Total width of the smoothing before compensation (two moving averages of half of it, s, 0 … 1):
  //! continuous jerk and snap for the dynamic method. Unset: compensation::kDefaultSmoothing_s when
  //! compensating, 0 without.
  std::optional<double> smooth_s;
  //! An input shaper following the tip's frequency: none, zv or zvd (FilterKind::smooth is refused).
  compensation::FilterKind shaper = compensation::FilterKind::none;

  motion::PlanOptions plan;  //!< limits, rate, work offset, dialect (motion's defaults: 5 g, 2 kHz, …)
  JerkRule jerk = JerkRule::planned;

  //! The laser's delays against the motion (s, ±0.05; positive: it lights late); the job switches it that much
  //! earlier (job::LaserTiming). Unset: the robot file's (laser.on_delay_ms, off_delay_ms; 0 when it gives none).
  std::optional<double> laser_on_delay_s, laser_off_delay_s;

  OutputFormat format = OutputFormat::csv;      //!< of a joint file written by the job
  std::uint64_t max_samples = kDefaultMaxSamples;  //!< cap on the samples written to a file
};

//! A JobSpec with the defaults for `robot`.
JobSpec default_job(kinematics::Robot robot);
//! The thesis's method on `robot`: its table fitted by the bilinear method (eqs. 4.8–4.12; for the presets
//! this is the built-in thesis-oc / thesis-sc model), the quasi-static correction of fig. 4.3 and no
//! reference filter (`stiffpath run --thesis`).
JobSpec thesis_job(kinematics::Robot robot);

//! The smoothing width a spec resolves to (s): smooth_s, or its default for compensate.
double smoothing_s(const JobSpec& spec) noexcept;

}  // namespace stiffpath::job
