// Output budgets: refuse an output before writing when it would not fit on its file system.
#pragma once

#include <filesystem>
#include <string>

namespace stiffpath::core {

//! Bytes available to an unprivileged user on the file system holding `directory` (statvfs), or a
//! negative value when it cannot be determined.
[[nodiscard]] double free_bytes(const std::filesystem::path& directory);

//! Writes a byte count for people: "812.0 kB", "2.4 GB".
[[nodiscard]] std::string human_bytes(double bytes);

//! Throws stiffpath::Error (naming `output`, the estimated size, the free space and `how_to_raise`)
//! when an estimated `bytes` exceeds the free space of the file system that will hold `output`.
//! Nothing is checked for "-" (stdout), FIFOs or devices, or when the free space is unknown.
void check_free_space(const std::filesystem::path& output, double bytes, const std::string& how_to_raise);

//! Checks, without creating anything, that `dir` is or can become a directory we write into (its
//! nearest existing ancestor is a writable directory), before long work whose results go there.
//! Throws stiffpath::Error naming the path and the reason (a file in the way, no permission).
void check_output_directory(const std::filesystem::path& dir);
//! check_output_directory, then creates `dir` and its parents; errors as stiffpath::Error.
void create_output_directory(const std::filesystem::path& dir);

}  // namespace stiffpath::core
