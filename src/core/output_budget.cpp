// Output budgets: the free space of the file system an output goes to, checked before writing (statvfs).
#include "stiffpath/core/output_budget.hpp"

#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <system_error>

#include "stiffpath/core/error.hpp"

namespace stiffpath::core {

namespace fs = std::filesystem;

double free_bytes(const fs::path& directory) {
  struct statvfs info {};
  if (::statvfs(directory.empty() ? "." : directory.c_str(), &info) != 0) return -1.0;
  return static_cast<double>(info.f_bavail) * static_cast<double>(info.f_frsize);
}

std::string human_bytes(double bytes) {
  if (bytes < 1e3) return fmt::format("{:.0f} B", bytes);
  if (bytes < 1e6) return fmt::format("{:.1f} kB", bytes * 1e-3);
  if (bytes < 1e9) return fmt::format("{:.1f} MB", bytes * 1e-6);
  return fmt::format("{:.1f} GB", bytes * 1e-9);
}

void check_free_space(const fs::path& output, double bytes, const std::string& how_to_raise) {
  if (output.empty() || output == "-") return;
  struct stat info {};
  if (::stat(output.c_str(), &info) == 0 && !S_ISREG(info.st_mode)) return;  // FIFO, device: written through
  const fs::path absolute = fs::absolute(output);
  const double available = free_bytes(absolute.parent_path());
  if (available < 0.0 || bytes <= available) return;
  throw Error(SourceLocation{output.string()},
              fmt::format("the output would take about {} but its file system has {} free; {}", human_bytes(bytes),
                          human_bytes(available), how_to_raise));
}

void check_output_directory(const fs::path& dir) {
  std::error_code ec;
  fs::path existing = fs::absolute(dir, ec);
  while (!fs::exists(fs::status(existing, ec)) && existing.has_parent_path() && existing != existing.parent_path()) {
    existing = existing.parent_path();
  }
  if (!fs::is_directory(fs::status(existing, ec))) {
    throw Error(SourceLocation{dir.string()}, "'" + existing.string() + "' exists and is not a directory (an output directory is needed here)");
  }
  if (::access(existing.c_str(), W_OK | X_OK) != 0) {
    throw Error(SourceLocation{dir.string()},
                "cannot write into '" + existing.string() + "': " + std::error_code(errno, std::generic_category()).message());
  }
}

void create_output_directory(const fs::path& dir) {
  check_output_directory(dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(SourceLocation{dir.string()}, "cannot create the output directory: " + ec.message());
}

}  // namespace stiffpath::core
