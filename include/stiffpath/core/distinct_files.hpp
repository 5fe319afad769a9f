// An output never replaces an input of the same command: the same path, or the same file through links.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace stiffpath::core {

//! A file a command reads or writes, with the option (or argument) that named it, for messages:
//! {"--robot", "r.json"}, {"-o", "out.csv"}, {"gcode", "job.gcode"}. An empty path (option not
//! given), "-" for an input and "builtin:…" are ignored.
struct NamedPath {
  std::string option;
  std::filesystem::path path;
};

//! Whether a and b are one file: the same device and inode (so through symbolic and hard links),
//! or, when either does not exist yet, the same absolute path with its links resolved.
[[nodiscard]] bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

//! The input that `output` would replace, if any: a regular file among `inputs` that is `output`
//! itself (same_file). FIFOs and devices (/dev/null) are written through, never replaced: never one.
[[nodiscard]] const NamedPath* replaced_input(const std::filesystem::path& output, const std::vector<NamedPath>& inputs);

//! Refuses, before anything is read at length or written, an output that would replace one of the
//! command's inputs, or that another of its outputs also writes (two "-" included):
//! stiffpath::Error "OUT: -o OUT is the same file as the input --robot IN (…)", exit 2 in the CLI.
void check_distinct_files(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

}  // namespace stiffpath::core
