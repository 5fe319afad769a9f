// Geometry calibration: the five-bar's actuators, links and joint zeros and the instrument's frame from tool-point readings.
#pragma once

#include <Eigen/Core>

#include <span>
#include <string>
#include <vector>

#include "stiffpath/calibration/geometry_model.hpp"
#include "stiffpath/calibration/geometry_readings.hpp"
#include "stiffpath/core/least_squares.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::calibration {

//! Settings of fit_geometry(), with documented defaults.
struct GeometryFitSettings {
  //! σ of one instrument coordinate (m): the measuring arm's ±23 µm taken as 2σ, as for the compliance campaigns.
  //! It decides which parameter directions the readings determine (below), not the stated uncertainties, whose
  //! σ is estimated from the fit's residuals.
  double noise_sigma_m = 11.5e-6;
  //! The parts' tolerances (each parameter's prior scale): how far from the robot file a real robot's actuator
  //! positions, link lengths (m) and joint zeros (rad) are expected to be. A direction of the parameters is
  //! determined when the readings fix it better than its prior scale (its σ below one scale unit), otherwise
  //! the parameters that carry it are held at the robot file's values and reported.
  double actuator_tolerance_m = 0.2e-3;
  double link_tolerance_m = 0.3e-3;
  double zero_tolerance_rad = 1.7453292519943296e-3;  //!< 0.1°
  //! The instrument frame's scales (it can be anywhere; these only set the finite-difference steps).
  double instrument_rotation_scale_rad = 1.0;
  double instrument_translation_scale_m = 1.0;
  core::LeastSquaresSettings solver;
};

//! Each parameter's scale (its prior size) in GeometryParameter order, SI.
Eigen::VectorXd parameter_scales(const GeometryFitSettings& settings);
//! The order in which parameters are held when the readings cannot separate them: the robot's frame first (the
//! left actuator's position, θ1's zero), so that a calibrated robot keeps the robot file's origin and
//! orientation, then the right actuator and θ2's zero, then the links.
std::span<const int> hold_order() noexcept;

//! One parameter of the result.
struct GeometryParameterResult {
  std::string name;        //!< parameter_name(): with its unit
  double nominal = 0.0;    //!< the robot file's value (instrument: its start estimate), SI
  double value = 0.0;      //!< fitted, SI
  double sigma = 0.0;      //!< standard uncertainty, SI (0 when fixed)
  bool fixed = false;      //!< held: the readings cannot separate it (see GeometryFitResult::undetermined)
  bool applicable = true;  //!< false for the instrument's tilt and height when the readings have no z
};

//! One reading's misfit before (the robot file's geometry, the instrument frame fitted alone) and after.
struct ReadingResidual {
  int line = 0;
  kinematics::Vec2 q_rad = kinematics::Vec2::Zero();
  Eigen::Vector3d before_m = Eigen::Vector3d::Zero();  //!< instrument coordinates, measured − predicted
  Eigen::Vector3d after_m = Eigen::Vector3d::Zero();
};

//! An undetermined direction: the parameters it moves together (scaled units, largest shares first) and its
//! singular value relative to the readings' noise.
struct UndeterminedDirection {
  std::vector<std::pair<std::string, double>> shares;  //!< parameter name → component (|components| ≥ 0.05)
  double singular_value_over_noise = 0.0;              //!< < 1: the readings fix it worse than its prior scale
};

struct GeometryFitResult {
  kinematics::FiveBarGeometry geometry;  //!< the calibrated geometry (modes kept)
  InstrumentFrame instrument;
  std::vector<GeometryParameterResult> parameters;  //!< kGeometryParameters, in GeometryParameter order
  std::vector<UndeterminedDirection> undetermined;
  std::vector<ReadingResidual> residuals;
  bool spatial = false;               //!< the readings had z
  bool mirrored = false;              //!< planar readings whose frame is mirrored (the instrument sees the plane from below)
  double rms_before_m = 0.0;          //!< RMS of the coordinates' misfits
  double rms_after_m = 0.0;
  double max_before_m = 0.0;          //!< largest |misfit vector| of a reading
  double max_after_m = 0.0;
  double sigma_estimated_m = 0.0;     //!< √(Σr² / (m − fitted)): the readings' noise as the fit sees it
  int fitted = 0;                     //!< parameters fitted
  int readings = 0;
  core::LeastSquaresStop stop = core::LeastSquaresStop::running;
  int iterations = 0;
  //! Parameter covariance over every parameter (SI), from the estimated σ.
  Eigen::MatrixXd covariance;
  //! The fit's parameter vector and start rotation, to predict readings at other poses (GeometryModel).
  Eigen::VectorXd x;
  Eigen::Matrix3d start_rotation = Eigen::Matrix3d::Identity();
};

//! Fits the geometry of `nominal` (its actuators, links and joint zero offsets) and the instrument's frame to
//! the readings by Levenberg–Marquardt (core::least_squares), from the robot file's geometry and the frame that
//! best maps its end points onto the readings (Umeyama's similarity without scale; for planar readings the
//! mirrored frame too). The parameters the readings cannot separate — the robot's position and rotation in
//! the instrument's frame always (3 directions), others when the poses are poorly spread — are held at the
//! robot file's values: the left actuator's position and θ1's zero first, so that the calibrated robot keeps
//! the file's frame. Throws stiffpath::Error (naming the readings' file and line) when a pose cannot be closed
//! by the robot file's geometry, or there are fewer coordinates than parameters to fit.
GeometryFitResult fit_geometry(const kinematics::Robot& nominal, const GeometryReadings& readings,
                               const GeometryFitSettings& settings = {});

//! `nominal` with the calibrated geometry: everything else kept, its compliance table and rows resolved to
//! absolute paths, its compliance model file dropped (fitted for the old geometry: `notes` says so, and how to
//! refit). The home position is kept when still reachable (else dropped, with a note).
kinematics::Robot calibrated_robot(const kinematics::Robot& nominal, const GeometryFitResult& fit,
                                   std::vector<std::string>* notes = nullptr);

}  // namespace stiffpath::calibration
