// `stiffpath linuxcnc config`: a complete LinuxCNC configuration (INI, HAL, tool table) for one robot file.
#include <cmath>
#include <fmt/format.h>
#include <memory>

#include "cmd_linuxcnc.hpp"
#include "commands.hpp"
#include "motion_flags.hpp"
#include "robot_flags.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/motion/gcode_limits.hpp"
#include "stiffpath/motion/limits.hpp"

namespace stiffpath::cli::linuxcnc {

namespace fs = std::filesystem;

namespace {

struct ConfigArgs {
  std::string robot;
  ModelFlags request;
  std::string output;
  std::string accel = "2g";
  double max_velocity_mm_s = units::m_to_mm(motion::default_max_velocity_m_s);
  long long servo_period_ns = 500000;
  double s_max = 1000.0;
  std::vector<double> workspace_mm;  // x_min, x_max, y_min, y_max
};

// The command that writes this configuration again (the output folder left out), for the INI's header.
std::string command_line(const ConfigArgs& a) {
  std::string text = "stiffpath linuxcnc config --robot " + a.robot;
  if (!a.request.model.empty()) text += " --model " + a.request.model;
  if (!a.request.method.empty()) text += " --method " + a.request.method;
  text += fmt::format(" --accel {} --max-velocity-mm-s {:g} --servo-period-ns {} --s-max {:g}", a.accel, a.max_velocity_mm_s,
                      a.servo_period_ns, a.s_max);
  if (!a.workspace_mm.empty()) text += fmt::format(" --workspace-mm {:g}", fmt::join(a.workspace_mm, ","));
  return text;
}

// Everything the files are written from, checked.
struct Machine {
  kinematics::Robot robot;
  std::string robot_setting, model_setting;  // [STIFFPATH]ROBOT, MODEL
  compliance::GridBounds workspace_m;
  kinematics::Vec2 home_m, home_rad;
  double accel_m_s2 = 0.0, velocity_m_s = 0.0;
};

// The points of the rectangle every 1/40 of its sides: all must be reachable within the joint limits.
void check_workspace(const kinematics::Robot& robot, const compliance::GridBounds& b) {
  constexpr int n = 40;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const kinematics::Vec2 p(b.x_min + (b.x_max - b.x_min) * i / n, b.y_min + (b.y_max - b.y_min) * j / n);
      const std::string why = robot.refusal(p);
      if (!why.empty()) {
        throw Error(fmt::format("the workspace x {:.3f}..{:.3f} mm, y {:.3f}..{:.3f} mm is not all usable: at ({:.3f}, {:.3f}) mm: "
                                "{} (give a smaller one with --workspace-mm X_MIN,X_MAX,Y_MIN,Y_MAX)",
                                units::m_to_mm(b.x_min), units::m_to_mm(b.x_max), units::m_to_mm(b.y_min),
                                units::m_to_mm(b.y_max), units::m_to_mm(p.x()), units::m_to_mm(p.y()), why));
      }
    }
  }
}

compliance::GridBounds workspace(const ConfigArgs& a, const compliance::Model& model) {
  if (a.workspace_mm.empty()) return model.bounds();
  const auto& w = a.workspace_mm;
  for (const double v : w) {
    if (!(std::abs(v) <= units::m_to_mm(motion::max_coordinate_m))) {
      throw Error(fmt::format("--workspace-mm: {} is not a coordinate within ±{:g} mm", v, units::m_to_mm(motion::max_coordinate_m)));
    }
  }
  if (!(w[0] < w[1] && w[2] < w[3])) {
    throw Error(fmt::format("--workspace-mm {:g},{:g},{:g},{:g}: expected X_MIN < X_MAX and Y_MIN < Y_MAX", w[0], w[1], w[2], w[3]));
  }
  return {units::mm_to_m(w[0]), units::mm_to_m(w[1]), units::mm_to_m(w[2]), units::mm_to_m(w[3])};
}

Machine check(const ConfigArgs& a, std::unique_ptr<compliance::LoadedModel>& loaded) {
  Machine m;
  m.robot = load_robot_flag(a.robot);
  const auto& robot = m.robot;
  m.robot_setting = robot.preset ? robot.name : fs::absolute(robot.file.path).lexically_normal().string();
  if (a.request.force) {
    throw Error("--force-model: a configuration cannot carry it (stiffpathcomp and stiffpath run would refuse a model "
                "fitted for another geometry); fit one for this robot with `stiffpath fit --robot ...`");
  }
  loaded = std::make_unique<compliance::LoadedModel>(compliance::load_robot_model(robot, model_request(a.request)));
  const bool builtin = !a.request.model.empty() && compliance::is_builtin_model(a.request.model);
  m.model_setting = builtin ? a.request.model : kModelName;

  if (!(a.servo_period_ns >= 100000 && a.servo_period_ns <= 10000000)) {
    throw Error(fmt::format("--servo-period-ns: must be within [100000, 10000000] (10 kHz .. 100 Hz), got {}", a.servo_period_ns));
  }
  if (!(a.s_max > 0.0 && a.s_max <= 1e9)) throw Error(fmt::format("--s-max: must be within (0, 1e9], got {}", a.s_max));
  try {
    m.accel_m_s2 = units::parse_acceleration_m_s2(a.accel);
  } catch (const Error& e) {
    throw Error(std::string("--accel: ") + e.what());
  }
  if (!(m.accel_m_s2 >= motion::min_acceleration_limit_m_s2 && m.accel_m_s2 <= motion::max_acceleration_limit_m_s2)) {
    throw Error(fmt::format("--accel: must be within [{:g}, {:g}] m/s^2, got {:g}", motion::min_acceleration_limit_m_s2,
                            motion::max_acceleration_limit_m_s2, m.accel_m_s2));
  }
  m.velocity_m_s = units::mm_to_m(a.max_velocity_mm_s);
  if (!(m.velocity_m_s >= motion::min_velocity_limit_m_s && m.velocity_m_s <= motion::max_velocity_limit_m_s)) {
    throw Error(fmt::format("--max-velocity-mm-s: must be within [{:g}, {:g}] mm/s, got {}", units::m_to_mm(motion::min_velocity_limit_m_s),
                            units::m_to_mm(motion::max_velocity_limit_m_s), a.max_velocity_mm_s));
  }

  m.workspace_m = workspace(a, *loaded->model);
  check_workspace(robot, m.workspace_m);
  if (!robot.home_m) throw Error(SourceLocation{robot.source()}, "home_mm: the robot file gives no home position, which homing needs");
  m.home_m = *robot.home_m;
  if (!m.workspace_m.contains(m.home_m)) {
    throw Error(SourceLocation{robot.source()}, fmt::format("home_mm ({:.3f}, {:.3f}) lies outside the workspace x {:.3f}..{:.3f} mm, "
                                                            "y {:.3f}..{:.3f} mm",
                                                            units::m_to_mm(m.home_m.x()), units::m_to_mm(m.home_m.y()),
                                                            units::m_to_mm(m.workspace_m.x_min), units::m_to_mm(m.workspace_m.x_max),
                                                            units::m_to_mm(m.workspace_m.y_min), units::m_to_mm(m.workspace_m.y_max)));
  }
  m.home_rad = robot.inverse(m.home_m);  // eq. 2.2 in the robot's working mode, with its checks
  return m;
}

std::string joint_section(const Machine& m, int i) {
  const auto& joint = m.robot.joints[static_cast<std::size_t>(i)];
  const double home_deg = units::rad_to_deg(m.home_rad[i]);
  return fmt::format(R"([JOINT_{0}]
# {1}: the robot file's limits
TYPE = ANGULAR
MIN_LIMIT = {2:.6f}
MAX_LIMIT = {3:.6f}
MAX_VELOCITY = {4:.6f}
MAX_ACCELERATION = {5:.6f}
FERROR = 1.0
MIN_FERROR = 0.5
# Homing in place (no switches): the joint takes the angle of the robot's home where it stands.
HOME = {6:.10f}
HOME_OFFSET = {6:.10f}
HOME_SEARCH_VEL = 0
HOME_LATCH_VEL = 0
HOME_SEQUENCE = 0
)",
                     i, joint.name, units::rad_to_deg(joint.min_rad), units::rad_to_deg(joint.max_rad),
                     units::rad_to_deg(joint.max_velocity_rad_s), units::rad_to_deg(joint.max_acceleration_rad_s2), home_deg);
}

std::string ini_text(const ConfigArgs& a, const Machine& m) {
  const auto& w = m.workspace_m;
  const double v_mm_s = units::m_to_mm(m.velocity_m_s), a_mm_s2 = units::m_to_mm(m.accel_m_s2);
  std::string text = fmt::format(R"(# LinuxCNC configuration of the five-bar robot '{name}': stiffpath's kinematics (stiffpathkins), compensation
# (stiffpathcomp) and laser output (stiffpathlaser), drives simulated. Written by
#   {command} -o <folder>
# Run it: `linuxcnc machine.ini` (Axis), or headless `stiffpath linuxcnc run <this folder> JOB.ngc`.
# Real drives: see the comments in machine.hal and docs/linuxcnc.md.

[EMC]
VERSION = 1.1
MACHINE = stiffpath five-bar {name} (simulated)

[DISPLAY]
DISPLAY = axis
POSITION_OFFSET = RELATIVE
POSITION_FEEDBACK = COMMANDED
MAX_FEED_OVERRIDE = 1.0
DEFAULT_LINEAR_VELOCITY = {v_default:.6g}
MAX_LINEAR_VELOCITY = {v:.6g}
INCREMENTS = 10mm 1mm 0.1mm

# The one place that names the robot: stiffpathkins ([KINS]) and stiffpathcomp read ROBOT and MODEL from here, and
# so does `stiffpath linuxcnc run`. ROBOT: a preset or a robot file; MODEL: a built-in model or a model file
# (relative paths: relative to this folder). S_MAX: the S word of full laser power (M3/M4 S...).
[STIFFPATH]
ROBOT = {robot}
MODEL = {model}
S_MAX = {s_max:.9g}

[KINS]
KINEMATICS = stiffpathkins
JOINTS = 2

[EMCMOT]
EMCMOT = motmod
SERVO_PERIOD = {period}
COMM_TIMEOUT = 1.0

[TASK]
TASK = milltask
CYCLE_TIME = 0.010

[RS274NGC]
PARAMETER_FILE = machine.var

[HAL]
HALFILE = machine.hal

[EMCIO]
EMCIO = io
CYCLE_TIME = 0.100
TOOL_TABLE = tool.tbl

[TRAJ]
COORDINATES = XY
LINEAR_UNITS = mm
ANGULAR_UNITS = degree
DEFAULT_LINEAR_VELOCITY = {v_default:.6g}
MAX_LINEAR_VELOCITY = {v:.6g}
# LinuxCNC 2.9's planner steps the acceleration, and with it the correction (docs/linuxcnc.md)
MAX_LINEAR_ACCELERATION = {acc:.6g}

# The workspace: {workspace_why}, reachable within the joint limits.
[AXIS_X]
MIN_LIMIT = {x0:.6f}
MAX_LIMIT = {x1:.6f}
MAX_VELOCITY = {v:.6g}
MAX_ACCELERATION = {acc:.6g}

[AXIS_Y]
MIN_LIMIT = {y0:.6f}
MAX_LIMIT = {y1:.6f}
MAX_VELOCITY = {v:.6g}
MAX_ACCELERATION = {acc:.6g}

# Joint angles in degrees; home = the robot file's home_mm ({hx:.6f}, {hy:.6f}) mm through its inverse kinematics.
)",
                                 fmt::arg("name", m.robot.name), fmt::arg("command", command_line(a)),
                                 fmt::arg("v_default", v_mm_s / 10.0), fmt::arg("v", v_mm_s), fmt::arg("robot", m.robot_setting),
                                 fmt::arg("model", m.model_setting), fmt::arg("s_max", a.s_max), fmt::arg("period", a.servo_period_ns),
                                 fmt::arg("acc", a_mm_s2),
                                 fmt::arg("workspace_why", a.workspace_mm.empty() ? "the compliance model's measured rectangle, where it holds"
                                                                                   : "as given by --workspace-mm"),
                                 fmt::arg("x0", units::m_to_mm(w.x_min)), fmt::arg("x1", units::m_to_mm(w.x_max)),
                                 fmt::arg("y0", units::m_to_mm(w.y_min)), fmt::arg("y1", units::m_to_mm(w.y_max)),
                                 fmt::arg("hx", units::m_to_mm(m.home_m.x())), fmt::arg("hy", units::m_to_mm(m.home_m.y())));
  text += joint_section(m, 0) + "\n" + joint_section(m, 1);
  text += fmt::format(R"(
# The streamed route (stream.hal, `stiffpath linuxcnc run --route stiffpath`): samples the FIFO holds ({:.1f} s).
[STREAM]
DEPTH = {}
)",
                      4000.0 * static_cast<double>(a.servo_period_ns) * 1e-9, 4000);
  return text;
}

}  // namespace

// The HAL files: machine.hal (LinuxCNC's route) and stream.hal (the streamed route). Defined in cmd_linuxcnc_hal.cpp.
std::string machine_hal();
std::string stream_hal();

namespace {

void write_config(const ConfigArgs& a) {
  std::unique_ptr<compliance::LoadedModel> loaded;
  const Machine m = check(a, loaded);
  AtomicDirectory dir(a.output);
  dir.write(kIniName, ini_text(a, m));
  dir.write(kHalName, machine_hal());
  dir.write(kStreamHalName, stream_hal());
  dir.write(kToolTableName, "T1 P1 D0 Z0 ;laser head\n");
  if (m.model_setting == kModelName) compliance::save_model((dir.path() / kModelName).string(), *loaded->model, loaded->provenance);
  dir.commit();
  fmt::print("{}: LinuxCNC configuration of {} ({}), model {}\n", a.output, m.robot.name, m.robot_setting, loaded->label);
  fmt::print("  workspace x {:.3f}..{:.3f} mm, y {:.3f}..{:.3f} mm; home ({:.3f}, {:.3f}) mm = theta ({:.6f}, {:.6f}) deg\n",
             units::m_to_mm(m.workspace_m.x_min), units::m_to_mm(m.workspace_m.x_max), units::m_to_mm(m.workspace_m.y_min),
             units::m_to_mm(m.workspace_m.y_max), units::m_to_mm(m.home_m.x()), units::m_to_mm(m.home_m.y()),
             units::rad_to_deg(m.home_rad.x()), units::rad_to_deg(m.home_rad.y()));
  fmt::print("  {:g} m/s^2, {:g} mm/s, servo period {} ns; run it: stiffpath linuxcnc run {} JOB.ngc\n", m.accel_m_s2,
             units::m_to_mm(m.velocity_m_s), a.servo_period_ns, a.output);
}

}  // namespace

void add_config_command(CLI::App& linuxcnc) {
  auto a = std::make_shared<ConfigArgs>();
  auto* cmd = linuxcnc.add_subcommand("config", "Write a LinuxCNC configuration (INI, HAL, tool table) for a robot, simulated drives");
  add_robot_flag(cmd, a->robot)->required()->description("Robot: a preset (oc-gu, oc-gl, sc-gu, sc-gl) or a robot file");
  add_model_flags(cmd, a->request);
  cmd->add_option("-o,--output", a->output, "The configuration's folder (new; written atomically)")->required();
  cmd->add_option("--accel", a->accel, "Acceleration limit of X and Y, e.g. 2g or 19.6 (m/s^2)")->capture_default_str();
  cmd->add_option("--max-velocity-mm-s", a->max_velocity_mm_s, "Speed limit of X and Y (mm/s)")->capture_default_str();
  cmd->add_option("--servo-period-ns", a->servo_period_ns, "Servo thread period (ns); the streamed route plans at its rate")
      ->capture_default_str();
  cmd->add_option("--s-max", a->s_max, "S of full laser power (GRBL $30: 1000; Marlin: 255)")->capture_default_str();
  cmd->add_option("--workspace-mm", a->workspace_mm,
                  "X_MIN,X_MAX,Y_MIN,Y_MAX of the axes (mm); default: the compliance model's measured rectangle")
      ->delimiter(',')
      ->expected(4);
  cmd->callback([a] { write_config(*a); });
}

}  // namespace stiffpath::cli::linuxcnc
