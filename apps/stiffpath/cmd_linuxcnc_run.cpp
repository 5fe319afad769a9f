// `stiffpath linuxcnc run`: one G-code job through a configuration of `linuxcnc config`, headless, recorded each period.
#include <unistd.h>

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <memory>

#include "cmd_linuxcnc.hpp"
#include "cmd_linuxcnc_compare.hpp"
#include "cmd_linuxcnc_record.hpp"
#include "cmd_linuxcnc_session.hpp"
#include "commands.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/job/joint_reader.hpp"

namespace stiffpath::cli::linuxcnc {

namespace fs = std::filesystem;

namespace {

constexpr std::uintmax_t kMaxJobBytes = 64u << 20;   // LinuxCNC reads the program itself; a bound for the copy
constexpr std::uintmax_t kMaxConfigFileBytes = 64u << 20;
constexpr double kMaxTimeout_s = 3600.0;
constexpr double kStartup_s = 120.0;  // LinuxCNC's start, homing and shutdown, beyond the job's own time limit

struct RunArgs {
  std::string config;  // the folder of `linuxcnc config`, or its INI file
  std::string job;
  std::string route = "linuxcnc";
  std::string record;
  std::string compare;
  std::string user;
  std::string work_dir;
  double timeout_s = 300.0;
  std::vector<std::string> run_options;  // after --: for `stiffpath run`
};

// What run needs of the configuration, read from its INI.
struct Machine {
  fs::path ini, folder;
  std::string robot_setting, model_setting;  // as `stiffpath run --robot/--model` takes them (paths absolute)
  std::string robot_copy, model_copy;        // for the INI's copy in the work folder (see copied_setting)
  kinematics::Robot robot;
  long long period_ns = 0;
  double accel_mm_s2 = 0.0, velocity_mm_s = 0.0, s_max = 0.0;
  long long stream_depth = 0;
};

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
  m.stream_depth = static_cast<long long>(ini.number("STREAM", "DEPTH", 10, 1e7));
  return m;
}

// A program beside this one (bin), or one of the helpers in libexec/stiffpath (found as stiffpath-vision is).
fs::path tool(const std::string& name, bool libexec) {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const fs::path bin = ec ? fs::path(".") : self.parent_path();
  return libexec ? (bin / fs::path(STIFFPATH_VISION_TOOL).parent_path() / name).lexically_normal() : bin / name;
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

// The work folder: --work-dir (kept), or a temporary one (removed at the end).
struct WorkDir {
  fs::path path;
  bool keep = false;
  explicit WorkDir(const std::string& requested) {
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
  ~WorkDir() {
    std::error_code ec;
    if (!keep) fs::remove_all(path, ec);
  }
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;
};

// The configuration's files, copied into work/config (LinuxCNC writes its parameter file there).
void copy_config(const Machine& m, const fs::path& to) {
  fs::create_directories(to);
  for (const auto& entry : fs::directory_iterator(m.folder)) {
    if (!entry.is_regular_file()) continue;
    if (entry.file_size() > kMaxConfigFileBytes) {
      throw Error(SourceLocation{entry.path().string()}, "larger than 64 MiB: not a file of a LinuxCNC configuration");
    }
    fs::copy_file(entry.path(), to / entry.path().filename(), fs::copy_options::overwrite_existing);
  }
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
  if (!out) throw Error(SourceLocation{file.string()}, "cannot write");
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The files the user LinuxCNC runs as must be able to read: the robot and model files outside the work folder.
std::vector<fs::path> outside_files(const Machine& m) {
  std::vector<fs::path> files;
  for (const auto& s : {m.robot_copy, m.model_copy}) {
    if (!s.empty() && s.front() == '/') files.emplace_back(s);
  }
  return files;
}

[[noreturn]] void failed(const std::string& what, const fs::path& log, const WorkDir& work, const RunUser& user,
                         const ProcessOutcome& outcome, bool with_log = true) {
  const std::string last = tail(log, 15);
  if (!with_log) throw Error(what);
  if (outcome.exit_code == kUnreadable) {
    throw Error(fmt::format("user '{}' cannot read {}: make it readable for that user, or name another with --user", user.name,
                            last.empty() ? "a file it needs" : last.substr(2, last.find('\n') - 2)));
  }
  throw Error(fmt::format("{}{}; the end of its log ({}):\n{}{}", what, outcome.timed_out ? " (stopped: out of time, see --timeout)" : "",
                          log.string(), last, work.keep ? "" : "(run with --work-dir DIR to keep every file)\n"));
}

// Run's additions to the configuration for LinuxCNC's route: the recorder, fed by machine.hal's signals.
std::string machine_record_hal() {
  return R"(# stiffpath linuxcnc run: every servo period after the compensation; positions scaled so that halsampler's six
# decimals resolve 1e-12 m (x, y in um) and 1e-9 degree (joints in millidegrees).
loadrt scale names=rec-x,rec-y,rec-j0-pos,rec-j1-pos,rec-j0-motor,rec-j1-motor,rec-j0-out,rec-j1-out
loadrt sampler depth=40000 cfg=fffffffffffbsbf
addf rec-x servo-thread
addf rec-y servo-thread
addf rec-j0-pos servo-thread
addf rec-j1-pos servo-thread
addf rec-j0-motor servo-thread
addf rec-j1-motor servo-thread
addf rec-j0-out servo-thread
addf rec-j1-out servo-thread
addf sampler.0 servo-thread
setp rec-x.gain 1000
setp rec-y.gain 1000
setp rec-j0-pos.gain 1000
setp rec-j1-pos.gain 1000
setp rec-j0-motor.gain 1000
setp rec-j1-motor.gain 1000
setp rec-j0-out.gain 1000
setp rec-j1-out.gain 1000
net x-cmd => rec-x.in
net y-cmd => rec-y.in
net j0-pos-cmd => rec-j0-pos.in
net j1-pos-cmd => rec-j1-pos.in
net j0-motor-cmd => rec-j0-motor.in
net j1-motor-cmd => rec-j1-motor.in
net j0-drive => rec-j0-out.in
net j1-drive => rec-j1-out.in
net rec-x-um rec-x.out => sampler.0.pin.0
net rec-y-um rec-y.out => sampler.0.pin.1
net rec-j0-pos-mdeg rec-j0-pos.out => sampler.0.pin.2
net rec-j1-pos-mdeg rec-j1-pos.out => sampler.0.pin.3
net rec-j0-motor-mdeg rec-j0-motor.out => sampler.0.pin.4
net rec-j1-motor-mdeg rec-j1-motor.out => sampler.0.pin.5
net rec-j0-out-mdeg rec-j0-out.out => sampler.0.pin.6
net rec-j1-out-mdeg rec-j1-out.out => sampler.0.pin.7
net rec-blend stiffpathcomp.blend => sampler.0.pin.8
net rec-dx stiffpathcomp.deflection-x-um => sampler.0.pin.9
net rec-dy stiffpathcomp.deflection-y-um => sampler.0.pin.10
net comp-fault => sampler.0.pin.11
net rec-status stiffpathcomp.status => sampler.0.pin.12
net laser-enable => sampler.0.pin.13
net laser-power => sampler.0.pin.14
net record => sampler.0.enable
sets record 0
)";
}

std::vector<RecordRow> run_linuxcnc_route(const Machine& m, const fs::path& job, const RunUser& user, const WorkDir& work,
                                          double timeout_s) {
  const fs::path config = work.path / "linuxcnc";
  copy_config(m, config);
  std::string ini = read_text(config / m.ini.filename());
  ini = ini_with(ini, "DISPLAY", "DISPLAY", "./stiffpath-linuxcnc-ui");
  ini = ini_without(ini, "DISPLAY", "OPEN_FILE");
  ini = ini_with_added(ini, "HAL", "HALFILE", "stiffpath-record.hal");
  ini = ini_with(ini, "STIFFPATH", "ROBOT", m.robot_copy);
  if (!m.model_copy.empty()) ini = ini_with(ini, "STIFFPATH", "MODEL", m.model_copy);
  write_text(config / "run.ini", ini);
  write_text(config / "stiffpath-record.hal", machine_record_hal());
  const fs::path ui = tool("stiffpath-linuxcnc-ui", true);
  if (!fs::exists(ui)) throw Error(SourceLocation{ui.string()}, "missing: the headless display of `stiffpath linuxcnc run` (a broken install)");
  fs::copy_file(ui, config / "stiffpath-linuxcnc-ui", fs::copy_options::overwrite_existing);
  fs::permissions(config / "stiffpath-linuxcnc-ui", fs::perms(0755), fs::perm_options::replace);
  fs::create_directories(work.path / "home");
  hand_over(work.path, user);

  const double rate_hz = 1e9 / static_cast<double>(m.period_ns);
  const auto env = headless_environment(
      work.path, user,
      {{"STIFFPATH_LCNC_PROGRAM", job.string()},
       {"STIFFPATH_LCNC_RECORD", (work.path / "machine-record.txt").string()},
       {"STIFFPATH_LCNC_RESULT", (work.path / "result.txt").string()},
       {"STIFFPATH_LCNC_TIMEOUT_S", fmt::format("{:g}", timeout_s)},
       {"STIFFPATH_LCNC_MAX_PERIODS", fmt::format("{:.0f}", std::ceil((timeout_s + 10.0) * rate_hz))}});
  const fs::path log = work.path / "linuxcnc.log";
  const auto outcome = run_process({"linuxcnc", "-r", "run.ini"}, user, config, env, log, timeout_s + kStartup_s, outside_files(m));
  (void)wait_for_rtapi_app_to_end(10.0);  // before the next session (--compare) or the caller's
  const std::string result = read_text(work.path / "result.txt");
  if (outcome.exit_code != 0 || result != "ok\n") {
    // LinuxCNC's own words about the job (a limit, a G-code error) say it all; otherwise its log does.
    const bool job_refused = result.rfind("LinuxCNC reported:", 0) == 0;
    failed(result.empty() ? std::string("LinuxCNC failed") : "LinuxCNC did not run the job: " + result.substr(0, result.size() - 1),
           log, work, user, outcome, !job_refused);
  }
  return read_machine_record(work.path / "machine-record.txt", m.robot, static_cast<double>(m.period_ns) * 1e-9);
}

// `stiffpath run` with the configuration's robot, model, limits and servo rate, then its stream.
void plan_with_stiffpath(const Machine& m, const fs::path& job, const std::vector<std::string>& options, const WorkDir& work) {
  const RunUser caller{"", ::geteuid(), ::getegid(), false};
  std::vector<std::string> argv{tool("stiffpath", false).string(), "run", job.string(), "--robot", m.robot_setting};
  if (!m.model_setting.empty()) argv.insert(argv.end(), {"--model", m.model_setting});
  argv.insert(argv.end(), {"--rate", fmt::format("{:.17g}", 1e9 / static_cast<double>(m.period_ns)), "--accel",
                           fmt::format("{:.17g}", m.accel_mm_s2 * 1e-3), "--max-velocity-mm-s", fmt::format("{:.17g}", m.velocity_mm_s),
                           "--s-max", fmt::format("{:.17g}", m.s_max), "--format", "bin", "-o", (work.path / "job.bin").string(),
                           "--quiet"});
  argv.insert(argv.end(), options.begin(), options.end());
  const char* path = std::getenv("PATH");
  const std::map<std::string, std::string> env{{"PATH", path ? path : "/usr/bin:/bin"}, {"LANG", "C.UTF-8"}};
  const fs::path log = work.path / "stiffpath-run.log";
  auto outcome = run_process(argv, caller, work.path, env, log, kMaxTimeout_s);
  if (outcome.exit_code != 0) throw Error(fmt::format("stiffpath run refused the job:\n{}", tail(log, 25)));
  outcome = run_process({tool("stiffpath-halstream", false).string(), (work.path / "job.bin").string(), "--period-ns",
                         std::to_string(m.period_ns), "-o", (work.path / "job.stream").string()},
                        caller, work.path, env, log, kMaxTimeout_s);
  if (outcome.exit_code != 0) throw Error(fmt::format("stiffpath-halstream failed:\n{}", tail(log, 10)));
}

std::vector<RecordRow> run_stiffpath_route(const Machine& m, const fs::path& job, const std::vector<std::string>& options,
                                           const RunUser& user, const WorkDir& work) {
  plan_with_stiffpath(m, job, options, work);
  job::JointReader reader((work.path / "job.bin").string());
  std::uint64_t samples = 0;
  while (reader.next()) ++samples;
  const double rate_hz = 1e9 / static_cast<double>(m.period_ns);
  const fs::path config = work.path / "halrun";
  copy_config(m, config);
  // The recorder: the stream sample number, the joints in millidegrees (1e-9 degree in halsampler's six decimals), laser, power.
  write_text(config / "stream-run.hal", fmt::format(R"(# stiffpath linuxcnc run: the streamed route, recorded every period.
source stream.hal
loadrt scale names=rec-j0,rec-j1
loadrt sampler depth=[STREAM]DEPTH cfg=uffbf
addf rec-j0 servo-thread
addf rec-j1 servo-thread
addf sampler.0 servo-thread
setp rec-j0.gain 1000
setp rec-j1.gain 1000
net stream-sample => sampler.0.pin.0
net j0-drive => rec-j0.in
net j1-drive => rec-j1.in
net rec-j0-mdeg rec-j0.out => sampler.0.pin.1
net rec-j1-mdeg rec-j1.out => sampler.0.pin.2
net laser-enable => sampler.0.pin.3
net laser-power => sampler.0.pin.4
loadusr halstreamer {}
start
loadusr -w halsampler -t -n {} {}
)",
                                                    (work.path / "job.stream").string(), samples + static_cast<std::uint64_t>(rate_hz / 2),
                                                    (work.path / "stream-record.txt").string()));
  fs::create_directories(work.path / "home");
  hand_over(work.path, user);
  const auto env = headless_environment(work.path, user, {});
  const fs::path log = work.path / "halrun.log";
  const double duration_s = static_cast<double>(samples) / rate_hz;
  const auto outcome = run_process({"halrun", "-i", m.ini.filename().string(), "-f", "stream-run.hal"}, user, config, env, log,
                                   duration_s + kStartup_s, outside_files(m));
  (void)wait_for_rtapi_app_to_end(10.0);
  if (outcome.exit_code != 0) failed("halrun failed to play the stream", log, work, user, outcome);
  return read_stream_record(work.path / "stream-record.txt", work.path / "job.bin", 1.0 / rate_hz);
}

void print_summary(const char* route, const std::vector<RecordRow>& rows, double period_s) {
  std::size_t on = 0;
  for (const auto& r : rows) on += r.laser;
  fmt::print("  {}: {} servo periods ({:.4f} s), laser on for {} ({:.4f} s)\n", route, rows.size(),
             static_cast<double>(rows.size()) * period_s, on, static_cast<double>(on) * period_s);
}

void run(const RunArgs& a) {
  const Machine m = read_machine(a.config);
  if (!(a.timeout_s > 0.0 && a.timeout_s <= kMaxTimeout_s)) throw Error(fmt::format("--timeout: must be within (0, {:g}] s, got {}", kMaxTimeout_s, a.timeout_s));
  std::error_code ec;
  const auto job_size = fs::file_size(a.job, ec);
  if (ec) throw Error(SourceLocation{a.job}, "cannot read the job: " + ec.message());
  if (job_size > kMaxJobBytes) throw Error(SourceLocation{a.job}, fmt::format("{} bytes: a job is at most 64 MiB here", job_size));
  const bool both = !a.compare.empty();
  if (both && !a.record.empty()) throw Error("--record and --compare: --compare writes both routes' records into its folder");
  if (!a.run_options.empty() && a.route == "linuxcnc" && !both) {
    throw Error("options after -- are for `stiffpath run`, which only the streamed route (--route stiffpath) or --compare uses");
  }
  if (!a.record.empty()) core::check_output_directory(fs::absolute(a.record).parent_path());
  std::unique_ptr<AtomicDirectory> compare_dir;
  if (both) compare_dir = std::make_unique<AtomicDirectory>(a.compare);
  check_linuxcnc_installed();
  const RunUser user = choose_user(a.user);
  WorkDir work(a.work_dir);
  const fs::path job = work.path / "job.ngc";
  fs::copy_file(a.job, job);
  const double period_s = static_cast<double>(m.period_ns) * 1e-9;

  fmt::print("{} in {} ({}):\n", a.job, m.ini.string(), m.robot.name);
  std::vector<RecordRow> linuxcnc_rows, stiffpath_rows;
  if (both || a.route == "linuxcnc") {
    linuxcnc_rows = run_linuxcnc_route(m, job, user, work, a.timeout_s);
    print_summary("LinuxCNC plans (stiffpathkins, stiffpathcomp, stiffpathlaser)", linuxcnc_rows, period_s);
  }
  if (both || a.route == "stiffpath") {
    stiffpath_rows = run_stiffpath_route(m, job, a.run_options, user, work);
    print_summary("stiffpath plans (stiffpath run, streamer)", stiffpath_rows, period_s);
  }
  if (!a.record.empty()) {
    write_record_csv(a.record, a.route == "linuxcnc" ? linuxcnc_rows : stiffpath_rows);
    fmt::print("  wrote {}\n", a.record);
  }
  if (both) {
    const fs::path dir = compare_dir->path();
    write_record_csv(dir / "linuxcnc.csv", linuxcnc_rows);
    write_record_csv(dir / "stiffpath.csv", stiffpath_rows);
    bool figure = false;
    const Comparison c = compare_routes(linuxcnc_rows, stiffpath_rows, m.robot, period_s, dir, figure);
    const nlohmann::json summary{
        {"job", a.job},
        {"robot", m.robot.name},
        {"comparable", c.comparable},
        {"largest_difference_um", c.comparable ? nlohmann::json(tidy(c.largest_difference_um)) : nlohmann::json(nullptr)},
        {"at_stretch", c.at_interval + 1},
        {"at_stretch_mm", tidy(c.at_path_mm)},
        {"laser_stretches", c.routes[0].intervals},
        {"routes",
         {{"linuxcnc",
           {{"duration_s", tidy(c.routes[0].duration_s)}, {"laser_s", tidy(c.routes[0].laser_s)},
            {"laser_path_mm", tidy(c.routes[0].laser_path_mm)}, {"largest_correction_um", tidy(c.routes[0].largest_correction_um)}}},
          {"stiffpath",
           {{"duration_s", tidy(c.routes[1].duration_s)}, {"laser_s", tidy(c.routes[1].laser_s)},
            {"laser_path_mm", tidy(c.routes[1].laser_path_mm)}, {"largest_correction_um", tidy(c.routes[1].largest_correction_um)}}}}}};
    core::write_file_atomically(dir / "compare.json", summary.dump(2) + "\n");
    compare_dir->commit();
    if (!c.comparable) {
      fmt::print(stderr, "warning: the routes switch the laser on {} and {} times: their laser paths cannot be paired, "
                         "so there is no difference and no figure\n", c.routes[0].intervals, c.routes[1].intervals);
    } else {
      fmt::print("  the two routes' commanded tool paths lie up to {:.1f} um apart (laser-on stretch {}, {:.1f} mm from its start); "
               "laser on over {:.1f} / {:.1f} mm for {:.4f} / {:.4f} s\n",
               c.largest_difference_um, c.at_interval + 1, c.at_path_mm, c.routes[0].laser_path_mm, c.routes[1].laser_path_mm,
               c.routes[0].laser_s, c.routes[1].laser_s);
    }
    fmt::print("  wrote {}/ (linuxcnc.csv, stiffpath.csv, compare.json{})\n", a.compare, figure ? ", compare.svg, compare.png" : "");
  }
  if (work.keep) fmt::print("  kept the work folder {}\n", work.path.string());
}

}  // namespace

void add_run_command(CLI::App& linuxcnc) {
  auto a = std::make_shared<RunArgs>();
  auto* cmd = linuxcnc.add_subcommand("run", "Run a G-code job in LinuxCNC headless (as root too) and record every servo period");
  cmd->add_option("config", a->config, "The folder written by `stiffpath linuxcnc config` (or its INI file)")->required();
  cmd->add_option("job", a->job, "G-code program")->required();
  cmd->add_option("run_options", a->run_options, "After --: options for `stiffpath run` (the streamed route)");
  cmd->add_option("--route", a->route,
                  "linuxcnc: LinuxCNC interprets and plans, stiffpathcomp corrects; stiffpath: `stiffpath run` plans and "
                  "compensates, streamer plays it")
      ->check(CLI::IsMember({"linuxcnc", "stiffpath"}))
      ->capture_default_str();
  cmd->add_option("--record", a->record, "CSV of every servo period: t_s,theta1_rad,theta2_rad,laser,power,x_mm,y_mm");
  cmd->add_option("--compare", a->compare,
                  "Run both routes and write their records, the difference and a figure into this new folder");
  cmd->add_option("--user", a->user, "As root: the unprivileged user LinuxCNC runs as (default: SUDO_USER, else 'stiffpath')");
  cmd->add_option("--work-dir", a->work_dir, "Keep LinuxCNC's files, logs and raw recordings in this new folder");
  cmd->add_option("--timeout", a->timeout_s, "Longest time the job may take in LinuxCNC (s)")->capture_default_str();
  cmd->callback([a] { run(*a); });
}

}  // namespace stiffpath::cli::linuxcnc
