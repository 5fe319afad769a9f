// Structural fits kept with the data they were fitted to: a fit is a pure function of the table and the geometry.
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/measurement/displacement_table.hpp"
#include "stiffpath/simulation/structural_compliance.hpp"

namespace stiffpath::simulation {

//! Bumped whenever fit_structural_model can give another answer for the same input; part of every key.
inline constexpr int kStructuralFitVersion = 2;

//! SHA-256 of what the fit reads: kStructuralFitVersion, the robot's geometry (its hash and the exact lengths and
//! actuator positions), its singularity margin and joints' lower limits (the kinematics the fit solves) and every
//! row's point, position, load direction, force and translations (17 significant digits).
std::string structural_fit_key(const kinematics::Robot& robot, const measurement::DisplacementTable& table);

//! The model's parameters in SI, every double written so that it reads back to the same bits.
nlohmann::json structural_fit_record(const StructuralModel& model);

//! The model a record describes, for `robot` over the measured rectangle `region`. Throws stiffpath::Error
//! when the record is incomplete.
std::shared_ptr<StructuralModel> structural_model_from_record(const kinematics::Robot& robot, const nlohmann::json& record,
                                                              const compliance::GridBounds& region);

//! The structural model of `robot` fitted to `table`: read from the fits compiled into the library
//! (data/twin/structural_fits.json) when one has this exact key, so the built-in robots' twins start without the
//! fit's 0.3–0.5 s; otherwise fitted (fit_structural_model). Either way the same model: a test refits every
//! stored entry and compares.
std::shared_ptr<StructuralModel> stored_or_fitted_structural_model(const kinematics::Robot& robot,
                                                                   const measurement::DisplacementTable& table);

}  // namespace stiffpath::simulation
