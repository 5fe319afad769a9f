// Identifying the tip's dynamics, a compliance correction and the laser's timing from a plate's measured marks.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/calibration/tip_response.hpp"
#include "stiffpath/core/least_squares.hpp"

namespace stiffpath::calibration {

//! One plate mark as the scan measured it, in the robot frame: its centre line in order from the stroke's
//! start to its end (a ringing stroke: to the tail's end).
struct ObservedMark {
  std::string id;              //!< the plate mark's id
  std::vector<Vec2> points_m;
};

//! Settings of the identification. Documented defaults.
struct IdentifyOptions {
  double point_sigma_m = 3e-6;   //!< uncertainty of one centre-line point across the mark (a 1200 dpi scan: ~2-3 µm)
  double end_sigma_m = 10e-6;    //!< uncertainty of a mark's end along it (the laser spot's end)
  double point_spacing_m = 50e-6;  //!< centre-line points used at least this far apart along the mark
  int max_iterations = 30;
  ResponseOptions response;
};

//! One identified quantity: its value before (the robot file's) and after, its standard uncertainty, and
//! whether the plate determined it (held otherwise, at its value before).
struct IdentifiedValue {
  std::string name;            //!< "sx0", …, "damping_ratio", "frequency_scale", "laser_on_delay_s", …
  double before = 0.0;
  double after = 0.0;
  double sigma = 0.0;          //!< standard uncertainty (0 when held)
  bool determined = true;      //!< false: the plate's marks do not determine it (small singular value), held
};

//! A mark's misfit (its normal distances and ends against the prediction), before and after.
struct MarkFit {
  std::string id;
  double rms_before_m = 0.0, rms_after_m = 0.0;  //!< of the normal distances
  double max_before_m = 0.0, max_after_m = 0.0;
  double end_before_m = 0.0, end_after_m = 0.0;  //!< the end's signed offset along the mark (measured − predicted)
  //! The normal distance along the mark, at the used points: arc length (m), before and after (m).
  std::vector<double> s_m, deviation_before_m, deviation_after_m;
};

//! What the plate says about the robot.
struct Identification {
  TipParameters before, after;
  std::vector<IdentifiedValue> values;
  std::vector<MarkFit> marks;
  //! The deflection per unit acceleration m·C, after over before, at each station's centre along x and y
  //! ((S·C·S)ii / Cii there), with its standard uncertainty.
  struct PointScale {
    Vec2 point_m = Vec2::Zero();
    Vec2 scale = Vec2::Ones();
    Vec2 sigma = Vec2::Zero();
  };
  std::vector<PointScale> scales;
  double rms_before_m = 0.0, rms_after_m = 0.0;
  int residuals = 0;
  int iterations = 0;
  core::LeastSquaresStop stop = core::LeastSquaresStop::running;
};

//! Fits the tip's parameters so that predict_marks() of `commands` (the plate's joint file) matches the
//! measured marks: each mark's centre-line points' normal distances to the predicted path (σ point_sigma_m) and
//! its two ends along it (σ end_sigma_m), by Levenberg–Marquardt from the robot's current values (the robot file's
//! damping ratio, frequency scale and laser delays; no correction). Directions the marks do not determine (the
//! scaled Jacobian's small singular values) are held at their value before and reported. Throws stiffpath::Error
//! when a plate mark has no laser pulse of the commands near its start, or no mark was measured.
Identification identify(const std::vector<compensation::JointCommand>& commands, const kinematics::Robot& robot,
                        const compliance::Model& model, const PlateDesign& plate,
                        const std::vector<ObservedMark>& observed, const IdentifyOptions& options = {});

}  // namespace stiffpath::calibration
