// AtomicFile: temporary-then-rename output that respects what the user named (stdout, FIFO, device, symlink).
#include "stiffpath/core/atomic_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <iostream>
#include <system_error>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/signal_cleanup.hpp"

namespace stiffpath::core {

namespace fs = std::filesystem;

namespace {
fs::path temporary_name(const fs::path& path) {
  static std::atomic<unsigned> counter{0};
  fs::path temp = path;
  temp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return temp;
}

// Follows a chain of symbolic links to the path finally written (which may not exist yet).
fs::path follow_links(const fs::path& path) {
  fs::path current = path;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(current, ec))) return current;
    const fs::path link = fs::read_symlink(current, ec);
    if (ec) throw Error(SourceLocation{path.string()}, "cannot read symbolic link: " + ec.message());
    current = link.is_absolute() ? link : current.parent_path() / link;
  }
  throw Error(SourceLocation{path.string()}, "too many levels of symbolic links");
}

fs::path directory_of(const fs::path& file) { return file.has_parent_path() ? file.parent_path() : fs::path("."); }
}  // namespace

AtomicFile::AtomicFile(fs::path path) : path_(std::move(path)) {
  if (path_ == "-") {
    stream_ = &std::cout;
    return;
  }
  target_ = follow_links(path_);
  directory_ = directory_of(target_);
  struct stat info {};
  if (::stat(target_.c_str(), &info) == 0) {
    if (S_ISDIR(info.st_mode)) throw Error(SourceLocation{path_.string()}, "is a directory, not a file");
    if (!S_ISREG(info.st_mode)) {  // FIFO, terminal, device: write through, never replace
      out_.open(target_, std::ios::binary | std::ios::out);
      if (!out_) throw Error(SourceLocation{path_.string()}, "cannot open for writing");
      return;
    }
  }
  temp_ = temporary_name(target_);
  out_.open(temp_, std::ios::binary | std::ios::trunc);
  if (!out_) throw Error(SourceLocation{path_.string()}, "cannot open for writing");
  slot_ = register_temporary(temp_.c_str());
}

AtomicFile::~AtomicFile() {
  if (committed_ || temp_.empty()) return;
  out_.close();
  std::error_code ignored;
  fs::remove(temp_, ignored);
  unregister_temporary(slot_);
}

void AtomicFile::commit() {
  stream_->flush();
  if (!*stream_) throw Error(SourceLocation{path_.string()}, "write failed (disk full?)");
  if (temp_.empty()) {
    if (out_.is_open()) out_.close();
    committed_ = true;
    return;
  }
  out_.close();
  if (!out_) throw Error(SourceLocation{path_.string()}, "write failed (disk full?)");
  std::error_code ec;
  fs::rename(temp_, target_, ec);
  if (ec) throw Error(SourceLocation{path_.string()}, "cannot rename temporary file: " + ec.message());
  unregister_temporary(slot_);
  committed_ = true;
}

void write_file_atomically(const fs::path& path, const std::string& text) {
  AtomicFile file(path);
  file.stream() << text;
  file.commit();
}

}  // namespace stiffpath::core
