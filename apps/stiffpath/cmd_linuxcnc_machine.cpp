// `stiffpath linuxcnc run`: what it reads of a configuration, the installation it checks, the folder it works in.
#include <unistd.h>

#include <fmt/format.h>

#include "cmd_linuxcnc.hpp"
#include "cmd_linuxcnc_routes.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"

namespace stiffpath::cli::linuxcnc {

namespace {

// A [STIFFPATH] value as the modules read it: relative paths from the INI's folder (stiffpath_ini.h).
std::string setting_path(const fs::path& folder, const std::string& value) {
  if (value.empty() || value.front() == '/') return value;
  const fs::path beside = folder / value;
  if (value.find('/') != std::string::npos || fs::exists(beside)) return fs::absolute(beside).lexically_normal().string();
  return value;  // a preset or built-in name
}

// A [STIFFPATH] value for the INI's copy beside the configuration's copied files: a file of the folder itself
// stays relative (it is copied too), another relative path becomes absolute.
std::string copied_setting(const fs::path& folder, const std::string& value) {
  if (value.empty() || value.front() == '/' || value.find('/') == std::string::npos) return value;
  return setting_path(folder, value);
}

}  // namespace

Machine read_machine(const std::string& config) {
  Machine m;
  m.ini = fs::is_directory(config) ? fs::path(config) / kIniName : fs::path(config);
  if (!fs::exists(m.ini)) {
    throw Error(SourceLocation{m.ini.string()}, "no such file: name a folder written by `stiffpath linuxcnc config`, or its INI file");
  }
  m.folder = fs::absolute(m.ini).parent_path();
  const IniFile ini(m.ini);
  m.robot_setting = setting_path(m.folder, ini.get("STIFFPATH", "ROBOT"));
  m.model_setting = setting_path(m.folder, ini.find("STIFFPATH", "MODEL").value_or(""));
  m.robot_copy = copied_setting(m.folder, ini.get("STIFFPATH", "ROBOT"));
  m.model_copy = copied_setting(m.folder, ini.find("STIFFPATH", "MODEL").value_or(""));
  try {
    m.robot = kinematics::load_robot(m.robot_setting);
  } catch (const Error& e) {
    throw Error(SourceLocation{m.ini.string()}, std::string("[STIFFPATH]ROBOT: ") + e.what());
  }
  const std::string units = ini.get("TRAJ", "LINEAR_UNITS");
  if (units != "mm" && units != "metric") {
    throw Error(SourceLocation{m.ini.string()}, "[TRAJ]LINEAR_UNITS = " + units + ": `stiffpath linuxcnc run` needs a configuration in mm");
  }
  m.period_ns = static_cast<long long>(ini.number("EMCMOT", "SERVO_PERIOD", 1e5, 1e7));
  m.accel_mm_s2 = ini.number("TRAJ", "MAX_LINEAR_ACCELERATION", 10.0, 1e7);
  m.velocity_mm_s = ini.number("TRAJ", "MAX_LINEAR_VELOCITY", 1.0, 1e5);
  m.s_max = ini.number("STIFFPATH", "S_MAX", 1e-6, 1e9);
  (void)ini.number("STREAM", "DEPTH", 10, 1e7);  // the streamed route's FIFO, read by stream.hal
  return m;
}

void check_linuxcnc_installed() {
  for (const auto& module : kModules) {
    const fs::path so = fs::path(kModuleDir) / (module + ".so");
    if (!fs::exists(so)) {
      throw Error(fmt::format("{} is missing: install stiffpath's LinuxCNC modules first (as root: cmake --build <build dir> "
                              "--target stiffpath_linuxcnc_install_modules, or cmake --install <build dir> --prefix /usr)",
                              so.string()));
    }
  }
  if (const pid_t other = wait_for_rtapi_app_to_end(10.0)) {
    throw Error(fmt::format("a LinuxCNC or halrun session is running (rtapi_app, pid {}); a machine has one real-time "
                            "environment: stop it first",
                            other));
  }
}

WorkDir::WorkDir(const std::string& requested) {
  if (!requested.empty()) {
    path = fs::absolute(requested);
    std::error_code ec;
    if (fs::exists(path, ec) && !(fs::is_directory(path, ec) && fs::is_empty(path, ec))) {
      throw Error(SourceLocation{requested}, "--work-dir: exists and is not an empty folder");
    }
    core::create_output_directory(path);
    keep = true;
  } else {
    std::string pattern = (fs::temp_directory_path() / "stiffpath-linuxcnc-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw Error("cannot create a temporary work folder in " + fs::temp_directory_path().string());
    path = pattern;
  }
  if (path.string().find_first_of(" \t\n") != std::string::npos) {
    throw Error(SourceLocation{path.string()}, "the work folder's path must not contain white space (HAL files name it)");
  }
}

WorkDir::~WorkDir() {
  std::error_code ec;
  if (!keep) fs::remove_all(path, ec);
}

}  // namespace stiffpath::cli::linuxcnc
