// The robot and model flags shared by every command, and the names of tables on the command line.
#include "robot_flags.hpp"

#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::cli {

CLI::Option* add_robot_flag(CLI::App* cmd, std::string& robot) {
  return cmd->add_option("--robot,--mechanism", robot,
                         "Robot: a preset (oc-gu, oc-gl, sc-gu, sc-gl) or a robot file (default: oc-gu)");
}

kinematics::Robot load_robot_flag(const std::string& robot) {
  return kinematics::load_robot(robot.empty() ? kDefaultRobot : robot);
}

std::vector<core::NamedPath> robot_inputs(const kinematics::Robot& robot, bool with_data,
                                          std::vector<core::NamedPath> more) {
  std::vector<core::NamedPath> inputs = std::move(more);
  const auto add = [&](const char* what, const core::DataRef& ref) {
    if (!ref.builtin && !ref.empty()) inputs.push_back({what, ref.path});
  };
  add("--robot", robot.file);
  if (with_data) {
    add("(the robot's table)", robot.compliance.table);
    add("(the robot's model)", robot.compliance.model);
  }
  return inputs;
}

void add_model_flags(CLI::App* cmd, ModelFlags& flags) {
  cmd->add_option("--model", flags.model,
                  "Compliance model file or built-in (thesis-oc, thesis-sc[-<method>]); default: the robot's own");
  cmd->add_option("--method", flags.method,
                  "Fit the robot's table with this method (" + core::enum_choices<compliance::FitMethod>() +
                      "; auto: the one cross-validation favours)");
  cmd->add_flag("--force-model", flags.force, "Use a model even if it was fitted for another robot geometry");
}

compliance::ModelRequest model_request(const ModelFlags& flags) {
  compliance::ModelRequest request;
  request.model = flags.model;
  request.force = flags.force;
  if (!flags.method.empty()) {
    request.refit = true;
    try {
      request.method = compliance::parse_fit_method(flags.method);
    } catch (const Error& e) {
      throw Error("--method: " + e.message());
    }
  }
  return request;
}

measurement::DataCheckOptions data_check_options(const kinematics::Robot& robot) {
  measurement::DataCheckOptions options;
  if (robot.replica) options.ul_m = robot.replica->ul_m;
  options.mirror_symmetric = robot.geometry.mirror_symmetric_about_x();
  return options;
}

core::DataRef table_ref(const std::string& argument) {
  return argument == "thesis" ? measurement::thesis_dataset() : core::parse_data_ref(argument);
}

}  // namespace stiffpath::cli
