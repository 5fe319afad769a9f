// Compliance model files (JSON): method, units, grid or parameters, fit statistics and provenance.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "stiffpath/compliance/model_factory.hpp"

namespace stiffpath::compliance {

inline constexpr const char* kModelFormat = "stiffpath-compliance-model";
inline constexpr int kModelFormatVersion = 1;

//! The model file document.
nlohmann::json model_to_json(const Model& model, const Provenance& provenance);
//! Writes the document atomically.
void save_model(const std::string& path, const Model& model, const Provenance& provenance);
//! Parses a document; `label` names it in errors ("model.json.nodes[3].C_um_per_N: …").
LoadedModel model_from_json(const nlohmann::json& document, const std::string& label);
//! Reads a model file.
LoadedModel load_model_file(const std::string& path);

}  // namespace stiffpath::compliance
