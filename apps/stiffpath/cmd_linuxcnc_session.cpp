// Running LinuxCNC's programs for `stiffpath linuxcnc run`: choosing and switching to its user, environment, time limit.
#include "cmd_linuxcnc_session.hpp"

#include <fcntl.h>
#include <grp.h>
#include <pwd.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fmt/format.h>
#include <fstream>
#include <optional>
#include <thread>

#include "stiffpath/core/error.hpp"

namespace stiffpath::cli::linuxcnc {

namespace fs = std::filesystem;

namespace {

constexpr const char* kSystemUser = "stiffpath";

std::optional<RunUser> find_user(const std::string& name) {
  struct passwd entry {};
  struct passwd* found = nullptr;
  std::vector<char> buffer(16384);
  if (::getpwnam_r(name.c_str(), &entry, buffer.data(), buffer.size(), &found) != 0 || found == nullptr) return std::nullopt;
  return RunUser{found->pw_name, found->pw_uid, found->pw_gid, false};
}

// useradd --system: no home, no login shell; what LinuxCNC needs is an unprivileged uid.
void create_system_user(const std::string& name) {
  const pid_t child = ::fork();
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) ::dup2(null, STDOUT_FILENO);
    ::execlp("useradd", "useradd", "--system", "--user-group", "--no-create-home", "--home-dir", "/nonexistent", "--shell",
             "/usr/sbin/nologin", name.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  if (child < 0 || ::waitpid(child, &status, 0) != child || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw Error(fmt::format("running as root: cannot create the system user '{}' for LinuxCNC (useradd failed); "
                            "name an existing unprivileged user with --user",
                            name));
  }
}

}  // namespace

RunUser choose_user(const std::string& requested) {
  if (::geteuid() != 0) {
    const struct passwd* self = ::getpwuid(::geteuid());
    const std::string name = self ? self->pw_name : std::to_string(::geteuid());
    if (!requested.empty() && requested != name) {
      throw Error(fmt::format("--user {}: only root can run LinuxCNC as another user (this is '{}')", requested, name));
    }
    return RunUser{name, ::geteuid(), ::getegid(), false};
  }
  std::string name = requested, why = "named by --user";
  const char* sudo_user = std::getenv("SUDO_USER");
  if (name.empty() && sudo_user != nullptr && *sudo_user != '\0' && std::string(sudo_user) != "root") {
    name = sudo_user;
    why = "the user who ran sudo";
  }
  bool created = false;
  if (name.empty()) {
    name = kSystemUser;
    why = "a system user for it";
    if (!find_user(name)) {
      create_system_user(name);
      created = true;
    }
  }
  auto user = find_user(name);
  if (!user) throw Error(fmt::format("--user {}: no such user", name));
  if (user->uid == 0) throw Error(fmt::format("--user {}: LinuxCNC refuses to run as root; name an unprivileged user", name));
  user->switched = true;
  std::fprintf(stderr, "stiffpath linuxcnc run: running as root, which LinuxCNC refuses, so LinuxCNC runs as user '%s' "
                       "(uid %u, %s%s; choose another with --user)\n",
               name.c_str(), static_cast<unsigned>(user->uid), why.c_str(), created ? ", created now with useradd --system" : "");
  return *user;
}

void hand_over(const fs::path& dir, const RunUser& user) {
  if (!user.switched) return;
  auto give = [&](const fs::path& p) {
    if (::lchown(p.c_str(), user.uid, user.gid) != 0) {
      throw Error(SourceLocation{p.string()}, fmt::format("cannot give it to user '{}'", user.name));
    }
  };
  give(dir);
  for (const auto& entry : fs::recursive_directory_iterator(dir)) give(entry.path());
}

std::map<std::string, std::string> headless_environment(const fs::path& work, const RunUser& user,
                                                        const std::map<std::string, std::string>& extra) {
  const char* path = std::getenv("PATH");
  std::map<std::string, std::string> env{{"PATH", path != nullptr && *path ? path : "/usr/local/bin:/usr/bin:/bin"},
                                         {"HOME", (work / "home").string()},
                                         {"USER", user.name},
                                         {"LOGNAME", user.name},
                                         {"LANG", "C.UTF-8"},
                                         {"RTAPI_FIFO_PATH", (work / "rtapi_fifo").string()}};
  for (const auto& [key, value] : extra) env[key] = value;
  return env;
}

ProcessOutcome run_process(const std::vector<std::string>& argv, const RunUser& user, const fs::path& cwd,
                           const std::map<std::string, std::string>& env, const fs::path& log, double timeout_s,
                           const std::vector<fs::path>& readable) {
  // Everything the child needs is prepared before fork: after it, only async-signal-safe calls.
  std::vector<std::string> env_text;
  for (const auto& [key, value] : env) env_text.push_back(key + "=" + value);
  std::vector<char*> child_env, child_argv;
  for (auto& e : env_text) child_env.push_back(e.data());
  child_env.push_back(nullptr);
  std::vector<std::string> args = argv;
  for (auto& a : args) child_argv.push_back(a.data());
  child_argv.push_back(nullptr);
  std::vector<std::string> readable_text;
  for (const auto& p : readable) readable_text.push_back(p.string());
  const std::string cwd_text = cwd.string(), log_text = log.string();
  std::string program = argv.at(0);
  if (program.find('/') == std::string::npos) {  // execve needs a path: look it up in the child's PATH now
    std::string search = env.count("PATH") ? env.at("PATH") : "/usr/bin:/bin";
    std::size_t start = 0;
    for (;;) {
      const std::size_t end = search.find(':', start);
      const fs::path candidate = fs::path(search.substr(start, end - start)) / program;
      if (::access(candidate.c_str(), X_OK) == 0) {
        program = candidate.string();
        break;
      }
      if (end == std::string::npos) throw Error(fmt::format("'{}' is not on the PATH (is LinuxCNC installed?)", argv[0]));
      start = end + 1;
    }
  }

  std::fflush(nullptr);
  const pid_t child = ::fork();
  if (child < 0) throw Error("cannot start a process: fork failed");
  if (child == 0) {
    const int out = ::open(log_text.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    const int in = ::open("/dev/null", O_RDONLY);
    if (out < 0 || in < 0) ::_exit(126);
    ::dup2(in, STDIN_FILENO);
    ::dup2(out, STDOUT_FILENO);
    ::dup2(out, STDERR_FILENO);
    if (user.switched) {
      const gid_t groups[1] = {user.gid};
      if (::setgroups(1, groups) != 0 || ::setgid(user.gid) != 0 || ::setuid(user.uid) != 0) {
        static const char message[] = "stiffpath: cannot switch to LinuxCNC's user\n";
        (void)!::write(STDERR_FILENO, message, sizeof message - 1);
        ::_exit(126);
      }
    }
    for (const auto& file : readable_text) {
      if (::access(file.c_str(), R_OK) != 0) {
        (void)!::write(STDERR_FILENO, file.data(), file.size());
        (void)!::write(STDERR_FILENO, "\n", 1);
        ::_exit(kUnreadable);
      }
    }
    if (::chdir(cwd_text.c_str()) != 0) ::_exit(126);
    ::execve(program.c_str(), child_argv.data(), child_env.data());
    ::_exit(127);
  }
  const auto start = std::chrono::steady_clock::now();
  const auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  ProcessOutcome outcome;
  bool terminated = false;
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(child, &status, WNOHANG);
    if (done == child) {
      outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      return outcome;
    }
    if (!terminated && seconds() > timeout_s) {
      ::kill(child, SIGTERM);  // the linuxcnc script's trap shuts the real-time environment down
      terminated = outcome.timed_out = true;
    } else if (terminated && seconds() > timeout_s + 20.0) {
      ::kill(child, SIGKILL);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

pid_t running_rtapi_app() {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream comm(entry.path() / "comm");
    std::string command;
    if (std::getline(comm, command) && command == "rtapi_app") return static_cast<pid_t>(std::stol(name));
  }
  return 0;
}

pid_t wait_for_rtapi_app_to_end(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  pid_t running = running_rtapi_app();
  while (running != 0 && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    running = running_rtapi_app();
  }
  return running;
}

std::string tail(const fs::path& file, int lines) {
  std::ifstream in(file);
  std::deque<std::string> last;
  for (std::string line; std::getline(in, line);) {
    last.push_back(line);
    if (static_cast<int>(last.size()) > lines) last.pop_front();
  }
  std::string text;
  for (const auto& line : last) text += "  " + line + "\n";
  return text;
}

}  // namespace stiffpath::cli::linuxcnc
