// Running LinuxCNC's programs for `stiffpath linuxcnc run`: the user they run as, their environment, time limits.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace stiffpath::cli::linuxcnc {

//! Who LinuxCNC runs as. rtapi_app refuses root, so a root caller hands the work over to another user.
struct RunUser {
  std::string name;
  uid_t uid = 0;
  gid_t gid = 0;
  bool switched = false;  //!< the caller is root and LinuxCNC runs as this user
};

//! The user: for a non-root caller, the caller (`requested` must be empty or the caller's name); for
//! root, `requested`, else SUDO_USER when that is not root, else the system user "stiffpath", created
//! with useradd when missing. Says on stderr which user and why. Throws stiffpath::Error.
RunUser choose_user(const std::string& requested);

//! Gives `dir` and everything in it to the user (a no-op unless switched).
void hand_over(const std::filesystem::path& dir, const RunUser& user);

//! The environment LinuxCNC runs headless in: PATH, the user's names, HOME and RTAPI_FIFO_PATH inside
//! `work` (LinuxCNC writes its logs and FIFO there), plus `extra`.
std::map<std::string, std::string> headless_environment(const std::filesystem::path& work, const RunUser& user,
                                                        const std::map<std::string, std::string>& extra);

struct ProcessOutcome {
  int exit_code = 0;       //!< the program's, or 128 + signal
  bool timed_out = false;  //!< stopped after `timeout_s`
};

//! Runs argv as `user` in `cwd` with exactly `env`, stdout and stderr into `log`, stdin /dev/null.
//! Before it starts, the user must be able to read every file of `readable` (else the outcome names
//! it: exit code kUnreadable and a line in the log). After `timeout_s` it gets SIGTERM, 20 s later SIGKILL.
ProcessOutcome run_process(const std::vector<std::string>& argv, const RunUser& user, const std::filesystem::path& cwd,
                           const std::map<std::string, std::string>& env, const std::filesystem::path& log,
                           double timeout_s, const std::vector<std::filesystem::path>& readable = {});
inline constexpr int kUnreadable = 97;

//! The process id of a running rtapi_app (LinuxCNC's or halrun's real-time environment), 0 if none.
pid_t running_rtapi_app();
//! Waits up to `seconds` for rtapi_app to end (it outlives the linuxcnc script and halrun by a moment);
//! returns the one still running, or 0.
pid_t wait_for_rtapi_app_to_end(double seconds);

//! The last `lines` lines of a text file (empty when unreadable), for error messages.
std::string tail(const std::filesystem::path& file, int lines);

}  // namespace stiffpath::cli::linuxcnc
