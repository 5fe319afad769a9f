// The robot and model flags shared by every command (--robot with its alias --mechanism, --model, --method, --force-model).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/data_ref.hpp"
#include "stiffpath/core/distinct_files.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/measurement/data_check.hpp"

namespace stiffpath::cli {

//! The robot used when a command names none.
inline constexpr const char* kDefaultRobot = "oc-gu";

//! Registers --robot (alias --mechanism): a preset or a robot file.
CLI::Option* add_robot_flag(CLI::App* cmd, std::string& robot);
//! The named robot, or the default preset when `robot` is empty.
kinematics::Robot load_robot_flag(const std::string& robot);

//! The files a robot brings with it, as inputs that a command's outputs may never replace
//! (core::check_distinct_files): its robot file and, with `with_data`, its table and model file;
//! built-in ones are left out; then `more`, the command's other inputs.
std::vector<core::NamedPath> robot_inputs(const kinematics::Robot& robot, bool with_data = true,
                                          std::vector<core::NamedPath> more = {});

//! The model flags as given: --model, --method, --force-model.
struct ModelFlags {
  std::string model;   //!< a model file or built-in name; empty: the robot's own
  std::string method;  //!< refit the robot's table: a method's name or auto; empty: no refit
  bool force = false;
};

//! Registers --model, --method and --force-model into `flags`.
void add_model_flags(CLI::App* cmd, ModelFlags& flags);
//! The library's request from the flags; throws stiffpath::Error "--method: …" for an unknown method.
compliance::ModelRequest model_request(const ModelFlags& flags);

//! The data checks as they apply to `robot`: |UL| of its replica (none: angles unchecked) and whether symmetry
//! about y = 0 is expected (its geometry is its own mirror image).
measurement::DataCheckOptions data_check_options(const kinematics::Robot& robot);

//! A displacement table named on the command line: "thesis" for the built-in data set, a file, or
//! "builtin:<path>".
core::DataRef table_ref(const std::string& argument);

}  // namespace stiffpath::cli
