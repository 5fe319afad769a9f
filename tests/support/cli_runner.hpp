// Test helper: runs the built stiffpath CLI and captures its exit code, stdout and stderr.
#pragma once

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace stiffpath::test {

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
  [[nodiscard]] nlohmann::json json() const { return nlohmann::json::parse(out); }
};

//! Runs `stiffpath <args>` (args are passed to /bin/sh as written) in `cwd`. With `timeout_s` > 0 the
//! run is stopped after that long (coreutils timeout: exit code 124), so a runaway job fails its test
//! instead of hanging the suite.
inline CliResult run_cli(const std::string& args, const std::filesystem::path& cwd = std::filesystem::current_path(),
                         int timeout_s = 0) {
  static int counter = 0;
  const auto err_path = std::filesystem::temp_directory_path() /
                        ("stiffpath_cli_err_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  const std::string limit = timeout_s > 0 ? "timeout " + std::to_string(timeout_s) + " " : std::string();
  const std::string command = "cd '" + cwd.string() + "' && " + limit + "'" + std::string(STIFFPATH_CLI) + "' " + args +
                              " 2>'" + err_path.string() + "'";
  CliResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_path);
  std::stringstream ss;
  ss << err.rdbuf();
  result.err = ss.str();
  std::filesystem::remove(err_path);
  return result;
}

//! A fresh empty directory under the system temp dir, removed by the destructor.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("stiffpath_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

//! Writes text to a file (test input).
inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

}  // namespace stiffpath::test
