// An output directory that appears complete or not at all: written in a staging directory, then moved in.
#pragma once

#include <filesystem>
#include <vector>

#include "stiffpath/core/distinct_files.hpp"

namespace stiffpath::core {

//! A directory of outputs (experiment, plot, report) written in a staging directory and moved into
//! place only by commit(), so that a failure (a full disk, gnuplot failing) or a signal leaves
//! nothing half-filled:
//! - a new directory is staged beside it as "<dir>.tmp-<pid>-<n>" and renamed as a whole;
//! - into an existing directory (figures added to `plots/`), the staging directory sits inside it
//!   ("<dir>/.tmp-<pid>-<n>", the same file system) and commit() renames each new file over its
//!   namesake, sub-directories merged, once every file is complete; other files stay as they were.
//! commit() first refuses (naming both) a file it would replace that is one of `inputs`, before it
//! moves anything. The staging directory is removed by the destructor unless committed, and by
//! install_signal_cleanup()'s handler on SIGINT, SIGTERM or SIGHUP. Not copyable.
class AtomicDirectory {
 public:
  //! Checks `dir` (core::check_output_directory), creates its missing parents and the staging
  //! directory. Throws stiffpath::Error naming the path.
  explicit AtomicDirectory(std::filesystem::path dir, std::vector<NamedPath> inputs = {});
  ~AtomicDirectory();
  AtomicDirectory(const AtomicDirectory&) = delete;
  AtomicDirectory& operator=(const AtomicDirectory&) = delete;

  //! Where the command writes (the staging directory).
  [[nodiscard]] const std::filesystem::path& staging() const noexcept { return staging_; }
  //! The directory the user named.
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return dir_; }

  //! Moves the staged files into place (see above). Throws stiffpath::Error naming the file.
  void commit();

 private:
  std::filesystem::path dir_, staging_;
  std::vector<NamedPath> inputs_;
  bool merge_ = false;  // dir_ existed: merge file by file
  int slot_ = -1;
  bool committed_ = false;
};

}  // namespace stiffpath::core
