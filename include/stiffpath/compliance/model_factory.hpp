// Building compliance models by method name, from a data table, a model file or the built-in thesis data.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::compliance {

//! Where a model came from, recorded in model files.
struct Provenance {
  std::string source;      //!< data file path, or "thesis" for the built-in data set
  std::string sha256;      //!< of the data file's bytes
  std::string mechanism;   //!< "OC" / "SC"
  ForceConvention convention = ForceConvention::measured;
};

//! A model together with its provenance.
struct LoadedModel {
  std::unique_ptr<Model> model;
  Provenance provenance;
};

//! Method names accepted by fit_model: bilinear (the thesis's), symmetric, physical (order 1),
//! physical-0, physical-2.
std::vector<std::string> method_names();

//! Fits `method` to the rows of `mechanism` in `table`. Throws stiffpath::Error for an unknown
//! method or mechanism (naming the ones available) and for data the method cannot use.
LoadedModel fit_model(const measurement::DisplacementTable& table, const std::string& mechanism,
                      const std::string& method, ForceConvention convention = ForceConvention::measured,
                      double link_length_m = 0.150);

//! A built-in model ("thesis-oc", "thesis-sc" = the thesis's bilinear model; "thesis-oc-<method>"
//! for another method), or a model file written by save_model. Errors name the file and field.
LoadedModel load_model(const std::string& name_or_path);
//! True when `name` is one of the built-in model names.
bool is_builtin_model(const std::string& name);

}  // namespace stiffpath::compliance
