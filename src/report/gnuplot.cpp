// gnuplot runner: writes a script, renders SVG and PNG under temporary names, renames on success, keeps the script.
#include "stiffpath/report/gnuplot.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <string_view>
#include <system_error>
#include <vector>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/signal_cleanup.hpp"

namespace stiffpath::report {

Style parse_style(const std::string& text) {
  if (text == "screen") return Style::screen;
  if (text == "paper") return Style::paper;
  throw Error(fmt::format("unknown figure style '{}' (known: screen, paper)", text));
}

namespace {
// The gnuplot executable on the PATH ("" when there is none), found without a shell.
std::string gnuplot_path() {
  const char* path = std::getenv("PATH");
  std::string_view dirs = path != nullptr ? path : "/usr/bin:/bin";
  while (!dirs.empty()) {
    const auto colon = dirs.find(':');
    const std::string dir(dirs.substr(0, colon));
    dirs = colon == std::string_view::npos ? std::string_view() : dirs.substr(colon + 1);
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

// Runs gnuplot in `dir` with its output in `log`, as a child that the signal handler kills and reaps
// (std::system would ignore SIGINT while it runs, so Ctrl-C would leave stiffpath writing on). The
// cleanup signals are blocked from the spawn until the child is registered. Returns waitpid's status.
int run_gnuplot(const std::filesystem::path& dir, const std::vector<std::string>& args, const std::string& log) {
  const std::string program = gnuplot_path();
  if (program.empty()) throw Error("gnuplot is not installed (scripts/bootstrap.sh installs gnuplot-nox)");
  std::vector<char*> argv;
  std::vector<std::string> storage{program};
  storage.insert(storage.end(), args.begin(), args.end());
  for (auto& a : storage) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // Absolute, since the log is opened after the change of directory.
  const std::string where = std::filesystem::absolute(dir).string(), log_path = std::filesystem::absolute(log).string();
  posix_spawn_file_actions_addchdir_np(&actions, where.c_str());
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t cleanup_signals, previous, none;
  sigemptyset(&cleanup_signals);
  sigemptyset(&none);
  for (const int signo : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&cleanup_signals, signo);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &cleanup_signals);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

  pthread_sigmask(SIG_BLOCK, &cleanup_signals, &previous);
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, program.c_str(), &actions, &attributes, argv.data(), environ);
  const int slot = spawned == 0 ? core::register_child(pid) : -1;
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned != 0) throw Error("cannot run gnuplot: " + std::error_code(spawned, std::generic_category()).message());
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  core::unregister_child(slot);
  return status;
}

// Whether gnuplot wrote a whole file: an SVG ends with its closing tag, a PNG with its IEND chunk
// (a full disk leaves them truncated, and gnuplot does not say so).
bool complete(const std::filesystem::path& file, bool svg) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) return false;
  const auto size = static_cast<std::streamoff>(in.tellg());
  const std::streamoff tail = std::min<std::streamoff>(size, 64);
  std::string end(static_cast<std::size_t>(tail), '\0');
  in.seekg(size - tail);
  in.read(end.data(), tail);
  if (!in) return false;
  if (svg) return end.find("</svg>") != std::string::npos;
  static const std::string iend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  return end.size() >= 12 && end.compare(end.size() - 12, 12, iend) == 0;
}

// Terminal lines for one output format. The output name can be overridden with -e "svg_out='…'" (render()
// does, to write under temporary names); run by hand the script writes <name>.svg / <name>.png.
std::string terminal(const Figure& f, bool svg) {
  const bool paper = f.style == Style::paper;
  const std::string font = paper ? (svg ? "serif,18" : "serif,16") : (svg ? "sans,12" : "sans,10");
  std::string out = svg ? fmt::format("set terminal svg size {},{} dynamic font '{}' noenhanced{}\n", f.width_px,
                                      f.height_px, font, paper ? " linewidth 1.5" : "")
                        : fmt::format("set terminal pngcairo size {},{} font '{}' noenhanced{}\n", f.width_px,
                                      f.height_px, font, paper ? " mono linewidth 1.5" : "");
  const char* var = svg ? "svg_out" : "png_out";
  out += fmt::format("set output (exists('{0}') ? {0} : {1})\n", var, quote(f.name + (svg ? ".svg" : ".png")));
  return out;
}
}  // namespace

bool gnuplot_available() { return !gnuplot_path().empty(); }

std::string quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string script(const Figure& f) {
  std::string out = fmt::format("# {}: drawn by stiffpath; edit and run `gnuplot {}.gp` in this folder to redraw.\n"
                                "set encoding utf8\n",
                                f.name, f.name);
  if (f.style == Style::paper) {
    // Black and white: dash patterns and point shapes tell the series apart, grey heat maps.
    out += "set monochrome\nset palette gray negative\n";
  }
  out += terminal(f, true) + f.commands + "\n";
  out += "reset\nset encoding utf8\n";
  if (f.style == Style::paper) out += "set monochrome\nset palette gray negative\n";
  // Drawn again rather than replotted: replot would redo only a multiplot's last panel.
  out += terminal(f, false) + f.commands + "\nunset output\n";
  return out;
}

void render(const std::filesystem::path& dir, const Figure& figure) {
  if (!gnuplot_available()) throw Error("gnuplot is not installed (scripts/bootstrap.sh installs gnuplot-nox)");
  const std::string stem = figure.name + ".tmp-" + std::to_string(::getpid());
  const std::filesystem::path script_file = dir / (stem + ".gp"), log = dir / (stem + ".log");
  const auto svg = dir / (stem + ".svg"), png = dir / (stem + ".png");
  // Every file of the figure under a temporary name that the signal handler removes.
  std::vector<int> slots;
  for (const auto* f : {&script_file, &log, &svg, &png}) slots.push_back(core::register_temporary(f->c_str()));
  std::error_code ignored;
  const auto remove_all = [&] {
    for (const auto* f : {&script_file, &log, &svg, &png}) std::filesystem::remove(*f, ignored);
    for (const int slot : slots) core::unregister_temporary(slot);
  };
  {
    std::ofstream out(script_file);
    out << script(figure);
    out.close();
    if (!out) {
      remove_all();
      throw Error(SourceLocation{script_file.string()}, "write failed (disk full?)");
    }
  }
  int status = 0;
  try {
    status = run_gnuplot(dir, {"-e", fmt::format("svg_out='{0}.svg'; png_out='{0}.png'", stem),
                               script_file.filename().string()},
                         log.string());
  } catch (...) {
    remove_all();
    throw;
  }
  std::ostringstream message;
  const bool exited = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!exited) message << std::ifstream(log).rdbuf();
  if (WIFSIGNALED(status)) message << "gnuplot was stopped by signal " << WTERMSIG(status);
  if (exited && !(complete(svg, true) && complete(png, false))) {
    message << "its SVG or PNG is incomplete (disk full?)";
  }
  if (!message.str().empty() || !exited) {
    remove_all();
    throw Error(SourceLocation{(dir / figure.name).string()}, "gnuplot failed: " + message.str());
  }
  std::filesystem::remove(log, ignored);
  std::filesystem::rename(svg, dir / (figure.name + ".svg"));
  std::filesystem::rename(png, dir / (figure.name + ".png"));
  std::filesystem::rename(script_file, dir / (figure.name + ".gp"));
  for (const int slot : slots) core::unregister_temporary(slot);
}

}  // namespace stiffpath::report
