// Shared plumbing of the libFuzzer harnesses: inputs as text or as a temporary file, and the one allowed failure.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>

namespace stiffpath::fuzz {

//! The fuzzer's bytes as a string.
inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

//! Writes the bytes to a file of this process (reused for every input) and returns its path, for the
//! loaders that read files by name. The file lives in $TMPDIR (default /tmp).
inline const std::string& as_file(const std::uint8_t* data, std::size_t size, const char* suffix) {
  static const std::string path = [suffix] {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir != nullptr ? dir : "/tmp") + "/stiffpath-fuzz-" + std::to_string(::getpid()) + suffix;
  }();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace stiffpath::fuzz

//! Every harness: a refusal (stiffpath::Error) is the expected outcome of bad input; any other
//! exception, crash or sanitizer report is a finding.
#define STIFFPATH_FUZZ_EXPECT_REFUSAL(body) \
  try {                                     \
    body                                    \
  } catch (const stiffpath::Error&) {       \
  }
