// AtomicFile: temporary-then-rename output so that failed runs leave nothing behind.
#include "stiffpath/core/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <system_error>

#include "stiffpath/core/error.hpp"

namespace stiffpath::core {

namespace {
std::filesystem::path temporary_name(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path temp = path;
  temp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return temp;
}
}  // namespace

AtomicFile::AtomicFile(std::filesystem::path path) : path_(std::move(path)), temp_(temporary_name(path_)) {
  out_.open(temp_, std::ios::binary | std::ios::trunc);
  if (!out_) throw Error(SourceLocation{path_.string()}, "cannot open for writing");
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(temp_, ignored);
}

void AtomicFile::commit() {
  out_.flush();
  if (!out_) throw Error(SourceLocation{path_.string()}, "write failed (disk full?)");
  out_.close();
  std::error_code ec;
  std::filesystem::rename(temp_, path_, ec);
  if (ec) throw Error(SourceLocation{path_.string()}, "cannot rename temporary file: " + ec.message());
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, const std::string& text) {
  AtomicFile file(path);
  file.stream() << text;
  file.commit();
}

}  // namespace stiffpath::core
