// What `stiffpath linuxcnc run` reads of a configuration, where it works, and the two routes it runs a job on.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "cmd_linuxcnc_record.hpp"
#include "cmd_linuxcnc_session.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::cli::linuxcnc {

namespace fs = std::filesystem;

//! What run needs of a configuration, read from its INI (errors name the file, line and value).
struct Machine {
  fs::path ini, folder;
  std::string robot_setting, model_setting;  // as `stiffpath run --robot/--model` takes them (paths absolute)
  std::string robot_copy, model_copy;        // for the INI's copy in the work folder (see copied_setting)
  kinematics::Robot robot;
  long long period_ns = 0;
  double accel_mm_s2 = 0.0, velocity_mm_s = 0.0, s_max = 0.0;
};

//! The configuration `config` (its folder, or its INI file), checked: the robot loads, the units are mm, the
//! periods, limits and S_MAX are numbers within range.
Machine read_machine(const std::string& config);

//! Refuses (stiffpath::Error) when a module is missing from LinuxCNC's module folder or another real-time
//! environment is still running after 10 s.
void check_linuxcnc_installed();

//! The work folder: `requested` (new or empty, kept), or a temporary one removed with this object.
struct WorkDir {
  fs::path path;
  bool keep = false;
  explicit WorkDir(const std::string& requested);
  ~WorkDir();
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;
};

//! LinuxCNC interprets and plans `job` (a copy in the work folder) in the configuration, with its display replaced by
//! stiffpath-linuxcnc-ui and a recorder added; one row per servo period from the program's start to its end.
std::vector<RecordRow> run_linuxcnc_route(const Machine& m, const fs::path& job, const RunUser& user, const WorkDir& work,
                                          double timeout_s);

//! `stiffpath run` plans `job` with the configuration's robot, model, limits and servo rate (and `options`),
//! stiffpath-halstream converts it, halrun plays it with stream.hal; one row per sample of the joint file.
std::vector<RecordRow> run_stiffpath_route(const Machine& m, const fs::path& job, const std::vector<std::string>& options,
                                           const RunUser& user, const WorkDir& work);

}  // namespace stiffpath::cli::linuxcnc
