// `stiffpath linuxcnc`: registers config and run, and the INI file and atomic folder they share.
#include "cmd_linuxcnc.hpp"

#include <unistd.h>

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "commands.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/signal_cleanup.hpp"

namespace stiffpath::cli {

namespace linuxcnc {

namespace fs = std::filesystem;

namespace {

constexpr std::uintmax_t kMaxIniBytes = 1 << 20;

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

// The section a line opens ("[NAME]" → NAME), if it is a section line.
std::optional<std::string> section_of(const std::string& line) {
  const std::string t = trim(line);
  if (t.size() >= 2 && t.front() == '[' && t.back() == ']') return t.substr(1, t.size() - 2);
  return std::nullopt;
}

// The key of a "KEY = VALUE" line, if it is one.
std::optional<std::string> key_of(const std::string& line) {
  const std::string t = trim(line);
  if (t.empty() || t[0] == '#' || t[0] == ';' || t[0] == '[') return std::nullopt;
  const auto equals = t.find('=');
  if (equals == std::string::npos) return std::nullopt;
  return trim(t.substr(0, equals));
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text += line + '\n';
  return text;
}

// Index one past the section's last line (its end), or nullopt when the section is missing.
std::optional<std::size_t> section_end(const std::vector<std::string>& lines, const std::string& section) {
  std::optional<std::size_t> end;
  bool inside = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (const auto s = section_of(lines[i])) {
      if (inside) return end;
      inside = *s == section;
    }
    if (inside) end = i + 1;
  }
  return end;
}

}  // namespace

IniFile::IniFile(const fs::path& path) : path_(path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) throw Error(SourceLocation{path.string()}, "cannot read the INI file: " + ec.message());
  if (size > kMaxIniBytes) throw Error(SourceLocation{path.string()}, fmt::format("{} bytes: an INI file is at most 1 MiB", size));
  std::ifstream in(path);
  if (!in) throw Error(SourceLocation{path.string()}, "cannot open the INI file");
  std::string section;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    lines_.push_back(line);
    if (const auto s = section_of(line)) {
      section = *s;
      continue;
    }
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#' || t[0] == ';') continue;
    const auto key = key_of(line);
    if (!key || key->empty()) {
      throw Error(SourceLocation{path.string(), number, 1}, "expected [SECTION], KEY = VALUE or a comment, got '" + t + "'");
    }
    entries_.push_back({section, *key, trim(t.substr(t.find('=') + 1)), number});
  }
}

const IniFile::Entry* IniFile::entry(const std::string& section, const std::string& key) const {
  for (const auto& e : entries_) {
    if (e.section == section && e.key == key) return &e;
  }
  return nullptr;
}

std::optional<std::string> IniFile::find(const std::string& section, const std::string& key) const {
  const Entry* e = entry(section, key);
  return e ? std::optional<std::string>(e->value) : std::nullopt;
}

std::string IniFile::get(const std::string& section, const std::string& key) const {
  const Entry* e = entry(section, key);
  if (!e) throw Error(SourceLocation{path_.string()}, fmt::format("[{}]{} is missing", section, key));
  return e->value;
}

double IniFile::number(const std::string& section, const std::string& key, double low, double high) const {
  const std::string text = get(section, key);
  const Entry* e = entry(section, key);
  const int column = static_cast<int>(lines_[static_cast<std::size_t>(e->line - 1)].find('=')) + 2;
  double value = 0.0;
  std::size_t used = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(value >= low && value <= high)) {
    throw Error(SourceLocation{path_.string(), e->line, column},
                fmt::format("[{}]{}: expected a number within [{:g}, {:g}], got '{}'", section, key, low, high, text));
  }
  return value;
}

std::string ini_with(const std::string& text, const std::string& section, const std::string& key, const std::string& value) {
  std::vector<std::string> lines = split_lines(text), out;
  std::string current;
  bool done = false;
  for (const auto& line : lines) {
    if (const auto s = section_of(line)) current = *s;
    if (current == section && key_of(line) == key) {
      if (!done) out.push_back(key + " = " + value);
      done = true;
      continue;
    }
    out.push_back(line);
  }
  if (done) return join_lines(out);
  return ini_with_added(join_lines(out), section, key, value);
}

std::string ini_with_added(const std::string& text, const std::string& section, const std::string& key,
                           const std::string& value) {
  std::vector<std::string> lines = split_lines(text);
  const std::string line = key + " = " + value;
  std::optional<std::size_t> after;  // one past the section's last KEY line
  std::string current;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (const auto s = section_of(lines[i])) current = *s;
    if (current == section && key_of(lines[i]) == key) after = i + 1;
  }
  if (!after) after = section_end(lines, section);
  if (!after) {
    lines.push_back("");
    lines.push_back("[" + section + "]");
    lines.push_back(line);
  } else {
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(*after), line);
  }
  return join_lines(lines);
}

std::string ini_without(const std::string& text, const std::string& section, const std::string& key) {
  std::vector<std::string> out;
  std::string current;
  for (const auto& line : split_lines(text)) {
    if (const auto s = section_of(line)) current = *s;
    if (current == section && key_of(line) == key) continue;
    out.push_back(line);
  }
  return join_lines(out);
}

AtomicDirectory::AtomicDirectory(fs::path target) : target_(std::move(target)) {
  std::error_code ec;
  if (target_.filename().empty()) target_ = target_.parent_path();  // "dir/" names dir
  if (fs::exists(fs::symlink_status(target_, ec))) {
    if (!fs::is_directory(target_, ec) || !fs::is_empty(target_, ec)) {
      throw Error(SourceLocation{target_.string()}, "exists and is not an empty folder: give a new folder's name");
    }
  }
  fs::path parent = fs::absolute(target_, ec).parent_path();
  fs::create_directories(parent, ec);
  if (ec) throw Error(SourceLocation{parent.string()}, "cannot create the folder: " + ec.message());
  std::string pattern = (parent / ("." + target_.filename().string() + ".tmp-XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    throw Error(SourceLocation{target_.string()}, fmt::format("cannot create a temporary folder in '{}': {}", parent.string(),
                                                               std::error_code(errno, std::generic_category()).message()));
  }
  temp_ = pattern;
}

AtomicDirectory::~AtomicDirectory() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(temp_, ec);
}

void AtomicDirectory::write(const std::string& name, const std::string& text, bool executable) const {
  const fs::path file = temp_ / name;
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw Error(SourceLocation{(target_ / name).string()}, "cannot write the file");
  std::error_code ec;
  fs::permissions(file, executable ? fs::perms(0755) : fs::perms(0644), fs::perm_options::replace, ec);
  if (ec) throw Error(SourceLocation{(target_ / name).string()}, "cannot set its permissions: " + ec.message());
}

void AtomicDirectory::commit() {
  std::error_code ec;
  // The folder is created by mkdtemp with mode 0700; the configuration is meant to be read by LinuxCNC's user.
  fs::permissions(temp_, fs::perms(0755), fs::perm_options::replace, ec);
  if (fs::exists(target_, ec)) fs::remove(target_, ec);  // an empty folder (checked in the constructor)
  fs::rename(temp_, target_, ec);
  if (ec) throw Error(SourceLocation{target_.string()}, "cannot rename the temporary folder into place: " + ec.message());
  committed_ = true;
}

}  // namespace linuxcnc

void add_linuxcnc_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("linuxcnc", "LinuxCNC: a machine configuration for a robot, and jobs run in it headless");
  cmd->require_subcommand(1);
  linuxcnc::add_config_command(*cmd);
  linuxcnc::add_run_command(*cmd);
}

}  // namespace stiffpath::cli
