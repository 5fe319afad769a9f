// `stiffpath linuxcnc config|run`: what the subcommand's source files share (docs/linuxcnc.md).
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace stiffpath::cli::linuxcnc {

//! The configuration's file names inside its folder (written by `config`, read by `run`).
inline constexpr const char* kIniName = "machine.ini";
inline constexpr const char* kHalName = "machine.hal";
inline constexpr const char* kStreamHalName = "stream.hal";
inline constexpr const char* kToolTableName = "tool.tbl";
inline constexpr const char* kModelName = "model.json";
//! The real-time modules the configuration loads, in LinuxCNC's module folder.
inline const std::vector<std::string> kModules{"stiffpathkins", "stiffpathcomp", "stiffpathlaser"};
inline constexpr const char* kModuleDir = "/usr/lib/linuxcnc/modules";

//! A LinuxCNC INI file as LinuxCNC reads it: "[SECTION]" lines, "KEY = VALUE" lines (a key may repeat,
//! as HALFILE does), comments starting with # or ;. Values are trimmed.
class IniFile {
 public:
  //! Reads `path`; throws stiffpath::Error naming the file (and line) when it cannot be read or a line
  //! is neither a section, a setting nor a comment. At most 1 MiB.
  explicit IniFile(const std::filesystem::path& path);

  //! The first value of KEY in [SECTION], if any.
  [[nodiscard]] std::optional<std::string> find(const std::string& section, const std::string& key) const;
  //! The value, or an error naming the file and the missing [SECTION]KEY.
  [[nodiscard]] std::string get(const std::string& section, const std::string& key) const;
  //! The value as a number within [low, high]; errors name the file, line and value.
  [[nodiscard]] double number(const std::string& section, const std::string& key, double low, double high) const;
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }
  //! The file's lines as read (for rewriting a copy).
  [[nodiscard]] const std::vector<std::string>& lines() const noexcept { return lines_; }

 private:
  struct Entry {
    std::string section, key, value;
    int line = 0;
  };
  [[nodiscard]] const Entry* entry(const std::string& section, const std::string& key) const;
  std::filesystem::path path_;
  std::vector<std::string> lines_;
  std::vector<Entry> entries_;
};

//! `ini`'s text with KEY in [SECTION] set to `value`: the first KEY line there replaced and any others
//! dropped, or a line appended to the section, which is created at the end when missing.
std::string ini_with(const std::string& text, const std::string& section, const std::string& key,
                     const std::string& value);
//! `ini`'s text with one more "KEY = VALUE" line after the section's last KEY line (or at its end).
std::string ini_with_added(const std::string& text, const std::string& section, const std::string& key,
                           const std::string& value);
//! `ini`'s text without any KEY line in [SECTION].
std::string ini_without(const std::string& text, const std::string& section, const std::string& key);

//! Writes a folder atomically: files go into a temporary folder beside `target`, which is renamed to
//! `target` by commit(). `target` must not exist or be an empty folder. Without commit() the temporary
//! folder is removed.
class AtomicDirectory {
 public:
  explicit AtomicDirectory(std::filesystem::path target);
  ~AtomicDirectory();
  AtomicDirectory(const AtomicDirectory&) = delete;
  AtomicDirectory& operator=(const AtomicDirectory&) = delete;
  //! Where to write now.
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return temp_; }
  //! Writes `name` inside it (text, or mode 0755 when `executable`).
  void write(const std::string& name, const std::string& text, bool executable = false) const;
  void commit();

 private:
  std::filesystem::path target_, temp_;
  bool committed_ = false;
};

void add_config_command(CLI::App& linuxcnc);
void add_run_command(CLI::App& linuxcnc);

}  // namespace stiffpath::cli::linuxcnc
