// The marks a job's joint commands make through a compliant tip: the calibration's model of what the scan shows.
#pragma once

#include <vector>

#include "stiffpath/compensation/samples.hpp"
#include "stiffpath/compliance/corrected_model.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::calibration {

using kinematics::Mat2;
using kinematics::Vec2;

//! What a calibration plate identifies, beyond the robot file's values.
struct TipParameters {
  //! The compliance field's correction (S symmetric): Q(p) = m·S(p)·C(p)·S(p), the deflection per unit acceleration.
  compliance::ComplianceCorrection correction;
  double damping_ratio = 0.05;    //!< ζ of the tip's modes
  double frequency_scale = 1.0;   //!< the tip's frequency over the one Q implies
  double laser_on_delay_s = 0.0;  //!< the laser lights this long after the command switches it on (against the motion)
  double laser_off_delay_s = 0.0; //!< and goes dark this long after it switches it off
};

//! The tool's path on the paper while the laser lights it, for one laser pulse of the commands.
struct PredictedMark {
  std::size_t first_command = 0;  //!< index of the pulse's first laser-on command
  Vec2 commanded_start_m = Vec2::Zero();  //!< the planned point where the command switched the laser on
  std::vector<Vec2> points_m;     //!< the tool point at the step rate, in time order
};

//! Settings of the prediction.
struct ResponseOptions {
  int steps_per_command = 10;     //!< integration steps per command interval (2 kHz commands: 20 kHz)
};

//! Predicts every laser pulse's mark: the base point follows the commanded joints (forward kinematics, cubic
//! Hermite between the commands, its acceleration linear), the tip relative to it obeys
//!   ë = −2ζ·A·ė − A²·(e + Q·p̈_b),   Q = m·S·C(p_b)·S,   A = s_f·Q^{−1/2},
//! (the thesis's tip on its compliance, eq. 4.4: at rest under a constant acceleration e = −Q·p̈_b; every mode
//! damped by ζ and ringing s_f times the frequency Q implies), starting at rest undeflected, and the tool point
//! p_b + e is recorded while the laser lights: from each laser-on command's time + the on delay to the next
//! laser-off command's time + the off delay. Semi-implicit Euler at steps_per_command steps per interval.
//! `commands` are a job's joint commands in time order (a joint file); `model` is the robot's compliance C.
std::vector<PredictedMark> predict_marks(const std::vector<compensation::JointCommand>& commands,
                                         const kinematics::Robot& robot, const compliance::Model& model,
                                         const TipParameters& parameters, const ResponseOptions& options = {});

}  // namespace stiffpath::calibration
