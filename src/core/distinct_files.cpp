// The check that keeps every command's outputs apart from its inputs and from each other.
#include "stiffpath/core/distinct_files.hpp"

#include <sys/stat.h>

#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::core {

namespace fs = std::filesystem;

namespace {
// A path that may not exist yet, absolute, with every symbolic link on the way followed (a link to a
// file still to be written included, which std::filesystem::weakly_canonical leaves as it is).
fs::path resolved(const fs::path& path) {
  std::error_code ec;
  fs::path current = fs::absolute(path, ec);
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(current, ec)); ++hops) {
    const fs::path link = fs::read_symlink(current, ec);
    if (ec) break;
    current = link.is_absolute() ? link : current.parent_path() / link;
  }
  return fs::weakly_canonical(current, ec).lexically_normal();
}

bool ignored(const NamedPath& p) {
  const std::string s = p.path.string();
  return s.empty() || s.starts_with("builtin:");
}

std::string how_linked(const fs::path& a, const fs::path& b) {
  if (fs::path(a).lexically_normal() == fs::path(b).lexically_normal()) return "";
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(a, ec)) || fs::is_symlink(fs::symlink_status(b, ec))) {
    return " (through a symbolic link)";
  }
  struct stat info {};
  if (::stat(a.c_str(), &info) == 0 && info.st_nlink > 1) return " (a hard link of it)";
  return " (the same file by another name)";
}
}  // namespace

bool same_file(const fs::path& a, const fs::path& b) {
  struct stat sa {}, sb {};
  const bool a_exists = ::stat(a.c_str(), &sa) == 0, b_exists = ::stat(b.c_str(), &sb) == 0;
  if (a_exists && b_exists) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (a_exists != b_exists) return false;
  return resolved(a) == resolved(b);
}

const NamedPath* replaced_input(const fs::path& output, const std::vector<NamedPath>& inputs) {
  if (output.empty() || output == "-") return nullptr;
  struct stat out {};
  if (::stat(output.c_str(), &out) != 0 || !S_ISREG(out.st_mode)) return nullptr;  // new, FIFO or device
  for (const auto& input : inputs) {
    if (ignored(input) || input.path == "-") continue;
    if (same_file(output, input.path)) return &input;
  }
  return nullptr;
}

void check_distinct_files(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& out = outputs[i];
    if (ignored(out)) continue;
    if (const NamedPath* in = replaced_input(out.path, inputs)) {
      throw Error(SourceLocation{out.path.string()},
                  fmt::format("{} {} is the same file as the input {} {}{}: an output never replaces an input of "
                              "its command; write it elsewhere",
                              out.option, out.path.string(), in->option, in->path.string(),
                              how_linked(out.path, in->path)));
    }
    for (std::size_t j = 0; j < i; ++j) {
      const NamedPath& other = outputs[j];
      if (ignored(other)) continue;
      const bool both_stdout = out.path == "-" && other.path == "-";
      if (!both_stdout && (out.path == "-" || other.path == "-")) continue;
      if (!both_stdout) {
        struct stat info {};
        // Two outputs through one FIFO or device are written through it in turn, not replaced.
        if (::stat(out.path.c_str(), &info) == 0 && !S_ISREG(info.st_mode)) continue;
      }
      if (both_stdout || same_file(out.path, other.path)) {
        throw Error(SourceLocation{out.path.string()},
                    fmt::format("{} {} is the same file as the output {} {}{}: one would overwrite the other; "
                                "give them different names",
                                out.option, out.path.string(), other.option, other.path.string(),
                                both_stdout ? "" : how_linked(out.path, other.path)));
      }
    }
  }
}

}  // namespace stiffpath::core
