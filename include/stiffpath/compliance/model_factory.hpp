// Building compliance models by method name from a robot's table, and loading model files and built-in models.
#pragma once

#include <memory>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/compliance/uncertainty.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::compliance {

//! How a model's method was chosen.
enum class MethodSelection : std::uint8_t {
  named,             //!< named by the caller or the robot file
  cross_validation,  //!< the method leave-one-out cross-validation favours (compliance::favoured_method)
};

//! Where a model came from and which robot it belongs to, recorded in model files.
struct Provenance {
  std::string source;      //!< the data table ("builtin:thesis/displacements.csv" or a path)
  std::string sha256;      //!< of the data table's bytes
  std::string rows;        //!< the table's `mechanism` rows it was fitted to ("OC"; empty: all)
  ForceConvention convention = ForceConvention::measured;
  std::string robot;       //!< name of the robot it was fitted for
  //! The robot's geometry; nullopt for files of format version 1, which did not record it.
  std::optional<kinematics::FiveBarGeometry> geometry;
  //! How the method was chosen (by name, or by cross-validation with the scores in `selection`).
  MethodSelection selected_by = MethodSelection::named;
  nlohmann::json selection;  //!< per method: mean leave-one-out error on the points all methods predict
  //! The uncertainty of the model's predictions (add_uncertainty(); model files record it); empty when unknown.
  std::optional<PredictionUncertainty> uncertainty;
};

//! A model together with its provenance and a name for messages.
struct LoadedModel {
  std::unique_ptr<Model> model;
  Provenance provenance;
  std::string label;  //!< "thesis-oc", a file's path, or "physical fitted to <table>"
};

//! Fits `method` to the rows `rows` of `table` (every row when empty) for `robot`, whose geometry the
//! physical models use and the provenance records. Unset: cross-validates every method that can run on
//! these points (compliance::cross_validate) and takes the one with the smallest mean error over the
//! points all of them predict. Throws stiffpath::Error for unknown rows (naming the ones available) and
//! for data the method cannot use (a grid method on an incomplete grid).
LoadedModel fit_model(const measurement::DisplacementTable& table, const std::string& rows,
                      std::optional<FitMethod> method, ForceConvention convention, const kinematics::Robot& robot);
//! A method named at an edge: "auto" (unset: cross-validation chooses) or one of FitMethod's names;
//! throws stiffpath::Error listing them.
std::optional<FitMethod> parse_fit_method(std::string_view text);

//! Learns the model's prediction uncertainty (estimate_method_uncertainty) from the table it was fitted to (its
//! provenance: source, rows, force convention) unless it has one. Throws stiffpath::Error when the table cannot be
//! read or the method's leave-one-out cannot run on it.
void add_uncertainty(LoadedModel& model);

//! A built-in model ("thesis-oc", "thesis-sc" = the thesis's bilinear model; "thesis-oc-<method>"
//! for another method: the preset oc-gu's or sc-gu's table and geometry), or a model file written by
//! save_model. Errors name the file, line and field.
LoadedModel load_model(const std::string& name_or_path);
//! True when `name` is one of the built-in model names.
bool is_builtin_model(const std::string& name);

//! What a command asks for besides the robot.
struct ModelRequest {
  std::string model;   //!< a model file or built-in name; empty: the robot's own
  //! Fit the robot's table instead of using its model file: with this method (when set), or, with
  //! `refit` and no method, the one cross-validation favours.
  std::optional<FitMethod> method;
  bool refit = false;
  bool force = false;  //!< accept a model fitted for another geometry
  std::string how_to_force = "pass --force-model";  //!< how the caller's surface says `force`, for the refusal
  ForceConvention convention = ForceConvention::measured;
};

//! The robot's compliance model: `request.model` if given; else the robot file's model file; else
//! its table fitted with `request.method`, the robot file's method, or the method cross-validation
//! favours. A model whose recorded geometry is not the robot's is refused (check_model_geometry)
//! unless `request.force`. Throws stiffpath::Error when the robot has no compliance data.
LoadedModel load_robot_model(const kinematics::Robot& robot, const ModelRequest& request = {});

//! Refuses (stiffpath::Error, naming both) a model fitted for another geometry than the robot's, or
//! one that does not record its geometry, unless `force`; the message names how the caller's surface forces it
//! (`how_to_force`: the CLI's "pass --force-model", Python's "pass force_model=True", …).
void check_model_geometry(const LoadedModel& model, const kinematics::Robot& robot, bool force,
                          std::string_view how_to_force = "pass --force-model");

//! The robot's displacement table restricted to its rows; throws when it has none.
measurement::DisplacementTable robot_table(const kinematics::Robot& robot);

//! The rectangle of a table's measurement points (its rows' positions), m.
GridBounds table_region(const measurement::DisplacementTable& table);

}  // namespace stiffpath::compliance

//! Names in model files: "named", "cross-validation".
template <>
struct stiffpath::core::EnumNames<stiffpath::compliance::MethodSelection> {
  static constexpr std::string_view what = "method selection";
  static constexpr std::array<std::pair<compliance::MethodSelection, std::string_view>, 2> names{
      {{compliance::MethodSelection::named, "named"}, {compliance::MethodSelection::cross_validation, "cross-validation"}}};
};
