// AtomicDirectory: a directory of outputs staged in full, then renamed as a whole or merged file by file.
#include "stiffpath/core/atomic_directory.hpp"

#include <unistd.h>

#include <atomic>
#include <string>
#include <system_error>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/core/signal_cleanup.hpp"

namespace stiffpath::core {

namespace fs = std::filesystem;

namespace {
std::string staging_suffix() {
  static std::atomic<unsigned> counter{0};
  return ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

// Every file under `from` (recursively) that would land on an existing path under `to`: refused when
// that path is one of the inputs, or a directory where a file goes (or the reverse).
void check_merge(const fs::path& from, const fs::path& to, const std::vector<NamedPath>& inputs) {
  for (const auto& entry : fs::directory_iterator(from)) {
    const fs::path target = to / entry.path().filename();
    std::error_code ec;
    const auto status = fs::status(target, ec);
    if (!fs::exists(status)) continue;
    if (entry.is_directory()) {
      if (!fs::is_directory(status)) throw Error(SourceLocation{target.string()}, "is in the way of a directory of outputs");
      check_merge(entry.path(), target, inputs);
      continue;
    }
    if (fs::is_directory(status)) throw Error(SourceLocation{target.string()}, "is a directory, in the way of an output file");
    if (const NamedPath* in = replaced_input(target, inputs)) {
      throw Error(SourceLocation{target.string()},
                  "this output is the same file as the input " + in->option + " " + in->path.string() +
                      ": an output never replaces an input of its command; write into another directory");
    }
  }
}

// Renames each file under `from` over its namesake under `to`; a directory new to `to` moves whole.
void merge(const fs::path& from, const fs::path& to) {
  for (const auto& entry : fs::directory_iterator(from)) {
    const fs::path target = to / entry.path().filename();
    std::error_code ec;
    if (entry.is_directory() && fs::is_directory(target, ec)) {
      merge(entry.path(), target);
      continue;
    }
    fs::rename(entry.path(), target, ec);
    if (ec) throw Error(SourceLocation{target.string()}, "cannot move the output into place: " + ec.message());
  }
}
}  // namespace

AtomicDirectory::AtomicDirectory(fs::path dir, std::vector<NamedPath> inputs)
    : dir_(std::move(dir)), inputs_(std::move(inputs)) {
  check_output_directory(dir_);
  std::error_code ec;
  merge_ = fs::is_directory(dir_, ec);
  if (merge_) {
    staging_ = dir_ / staging_suffix();
  } else {
    const fs::path parent = dir_.lexically_normal().parent_path();
    if (!parent.empty()) create_output_directory(parent);
    staging_ = dir_.lexically_normal();
    staging_ += staging_suffix();
  }
  if (!fs::create_directory(staging_, ec) || ec) {
    throw Error(SourceLocation{dir_.string()}, "cannot create a staging directory: " + ec.message());
  }
  slot_ = register_temporary_directory(staging_.c_str());
}

AtomicDirectory::~AtomicDirectory() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
  unregister_temporary(slot_);
}

void AtomicDirectory::commit() {
  std::error_code ec;
  if (!merge_) {
    // A directory that appeared meanwhile is merged into rather than replaced.
    fs::rename(staging_, dir_, ec);
    if (!ec) {
      unregister_temporary(slot_);
      committed_ = true;
      return;
    }
    if (!fs::is_directory(dir_)) throw Error(SourceLocation{dir_.string()}, "cannot move the outputs into place: " + ec.message());
  }
  check_merge(staging_, dir_, inputs_);
  merge(staging_, dir_);
  fs::remove_all(staging_, ec);
  unregister_temporary(slot_);
  committed_ = true;
}

}  // namespace stiffpath::core
