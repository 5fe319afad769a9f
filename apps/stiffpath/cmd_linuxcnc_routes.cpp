// `stiffpath linuxcnc run`: the two routes it runs a job on (LinuxCNC plans; stiffpath plans, streamer plays).
#include "cmd_linuxcnc_routes.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <map>

#include "cmd_linuxcnc.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/joint_reader.hpp"

namespace stiffpath::cli::linuxcnc {

namespace {

constexpr std::uintmax_t kMaxConfigFileBytes = 64u << 20;  // a file of a configuration folder, copied
constexpr double kMaxPlanTime_s = 3600.0;
constexpr double kStartup_s = 120.0;  // LinuxCNC's start, homing and shutdown, beyond the job's own time limit

// A program beside this one (bin), or one of the helpers in libexec/stiffpath (found as stiffpath-vision is).
fs::path tool(const std::string& name, bool libexec) {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const fs::path bin = ec ? fs::path(".") : self.parent_path();
  return libexec ? (bin / fs::path(STIFFPATH_VISION_TOOL).parent_path() / name).lexically_normal() : bin / name;
}

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

}  // namespace

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

namespace {

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
  auto outcome = run_process(argv, caller, work.path, env, log, kMaxPlanTime_s);
  if (outcome.exit_code != 0) throw Error(fmt::format("stiffpath run refused the job:\n{}", tail(log, 25)));
  outcome = run_process({tool("stiffpath-halstream", false).string(), (work.path / "job.bin").string(), "--period-ns",
                         std::to_string(m.period_ns), "-o", (work.path / "job.stream").string()},
                        caller, work.path, env, log, kMaxPlanTime_s);
  if (outcome.exit_code != 0) throw Error(fmt::format("stiffpath-halstream failed:\n{}", tail(log, 10)));
}

}  // namespace

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

}  // namespace stiffpath::cli::linuxcnc
