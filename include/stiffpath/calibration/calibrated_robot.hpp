// What a calibration writes: the identified robot file, its corrected compliance model, and the report.
#pragma once

#include <nlohmann/json.hpp>

#include <memory>
#include <string>

#include "stiffpath/calibration/identify.hpp"
#include "stiffpath/compliance/corrected_model.hpp"
#include "stiffpath/compliance/model_factory.hpp"

namespace stiffpath::calibration {

//! The files of a calibrated robot, as JSON documents.
struct CalibratedRobot {
  nlohmann::json robot;  //!< a robot file: the robot's own, with the identified damping ratio, frequency scale and
                         //!< laser delays (`laser`), and `compliance.model` naming the model file
  nlohmann::json model;  //!< a model file: the robot's model with the identified correction of its field
};

//! The robot and model files for `robot` after `id`: the correction is applied over the robot's model as it was
//! fitted or read (`base`). When `base` already carries a plate's correction (a second round), the two
//! corrections' product is refitted as one (at each point of a 9 × 9 grid over the plate's area the symmetric S that
//! gives the same S·C·S, then sx, sy and the cross term fitted linearly: a product of two linear corrections is not
//! linear, so a round may lose up to |Δ1·Δ2| of its slopes).
//! `model_file_name` is what the robot file's compliance.model says (beside the robot file). Undetermined values
//! stay as they were (identify holds them). Throws stiffpath::Error for a correction that is not positive over
//! the model's region.
CalibratedRobot calibrated_robot(const kinematics::Robot& robot, const compliance::LoadedModel& base,
                                 const Identification& id, const std::string& model_file_name);

//! The identification as a report: every value before and after with its uncertainty and whether the plate
//! determined it, the misfit before and after (overall and per mark), the deflection scale at each station.
nlohmann::json identification_json(const Identification& id);

}  // namespace stiffpath::calibration
