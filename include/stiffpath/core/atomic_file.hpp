// Atomic file output: write to a temporary name beside the target, rename on commit, remove on failure.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

namespace stiffpath::core {

//! An output file that appears under its final name only when commit() succeeds. If the object is
//! destroyed without commit() (an exception, an early return), the temporary file is removed, so a
//! failed run never leaves a half-written file. Not copyable.
class AtomicFile {
 public:
  //! Opens "<path>.tmp-<pid>-<n>" for writing (binary mode). Throws stiffpath::Error naming the path.
  explicit AtomicFile(std::filesystem::path path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  [[nodiscard]] std::ostream& stream() noexcept { return out_; }
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }

  //! Flushes, checks the stream, closes and renames onto the final path. Throws on any I/O failure.
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temp_;
  std::ofstream out_;
  bool committed_ = false;
};

//! Writes the whole text atomically (convenience for small outputs such as JSON documents).
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace stiffpath::core
