// Compliance model files (JSON): method, units, grid or parameters, fit statistics and provenance.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/json_fields.hpp"

namespace stiffpath::compliance {

inline constexpr const char* kModelFormat = "stiffpath-compliance-model";
inline constexpr int kModelFormatVersion = 2;  //!< 2 records the robot and its geometry; 1 is still read

//! A model's parameters and fit statistics as JSON, as model files hold them: a grid's nodes, a physical
//! model's D(p), a spline's weights, a tool point's lever, a calibration's correction. A model no file can hold
//! (the twin's structural truth) gives its description.
nlohmann::json model_parameters(const Model& model);

//! The model file document.
nlohmann::json model_to_json(const Model& model, const Provenance& provenance);
//! Writes the document atomically.
void save_model(const std::string& path, const Model& model, const Provenance& provenance);
//! Parses a document; errors name its file, line and field ("model.json:40:9: nodes[3].C_um_per_N: …").
LoadedModel model_from_json(const core::JsonDocument& document);
//! Reads a model file (on disk or built in).
LoadedModel load_model_file(const core::DataRef& file);

}  // namespace stiffpath::compliance
