// Atomic file output: write to a temporary name beside the target, rename on commit, remove on failure or signal.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

namespace stiffpath::core {

//! An output file that appears under its final name only when commit() succeeds. If the object is
//! destroyed without commit() (an exception, an early return), the temporary file is removed, so a
//! failed run never leaves a half-written file. What the user named is respected:
//! - "-" writes to standard output (nothing to rename; commit() flushes);
//! - a FIFO, character or block device is written through in place, never replaced;
//! - a symbolic link is followed: its final target is replaced atomically and the link itself is kept;
//! - a directory is refused.
//! The temporary file is registered so that install_signal_cleanup()'s handler can remove it. Not copyable.
class AtomicFile {
 public:
  //! Opens "<target>.tmp-<pid>-<n>" (or the FIFO/device/stdout itself) for writing, binary mode.
  //! Throws stiffpath::Error naming the path.
  explicit AtomicFile(std::filesystem::path path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  [[nodiscard]] std::ostream& stream() noexcept { return *stream_; }
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }
  //! The file system directory that will hold the output (for free-space checks); empty for stdout.
  [[nodiscard]] const std::filesystem::path& directory() const noexcept { return directory_; }

  //! Flushes, checks the stream, closes and renames onto the final path. Throws on any I/O failure.
  void commit();

 private:
  std::filesystem::path path_;       // what the user named
  std::filesystem::path target_;     // the regular file replaced on commit (a symlink's target)
  std::filesystem::path temp_;       // empty when written through (stdout, FIFO, device)
  std::filesystem::path directory_;  // where the bytes go
  std::ofstream out_;
  std::ostream* stream_ = &out_;
  int slot_ = -1;  // signal-cleanup registry slot
  bool committed_ = false;
};

//! Writes the whole text atomically (convenience for small outputs such as JSON documents).
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace stiffpath::core
