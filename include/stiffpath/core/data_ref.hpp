// A data file named by a robot file or on the command line: a path on disk, or a file built into the binary.
#pragma once

#include <cstddef>
#include <limits>
#include <string>

namespace stiffpath::core {

//! Where a data file lives. A robot file built into the binary names its data relative to itself, so
//! its references are built in too; a robot file on disk names files on disk (relative to its folder).
struct DataRef {
  std::string path;      //!< a filesystem path, or for a built-in file its path under data/ ("thesis/displacements.csv")
  bool builtin = false;  //!< compiled into the binary (core::find_embedded)

  [[nodiscard]] bool empty() const noexcept { return path.empty(); }
  //! How errors and outputs name it: the path, or "builtin:<path>".
  [[nodiscard]] std::string label() const;
  [[nodiscard]] bool operator==(const DataRef& other) const noexcept = default;
};

//! `relative` as seen from the file `base`: resolved against its folder and normalised (an absolute
//! path stays as it is, and only on disk; "builtin:<path>" names a built-in file). Built-in bases
//! give built-in references.
DataRef resolve_beside(const DataRef& base, const std::string& relative);
//! A command-line name: "builtin:<path>" for a built-in file, anything else a path on disk.
DataRef parse_data_ref(const std::string& text);
//! The file's bytes; throws stiffpath::Error naming it when it cannot be read, or when it holds more
//! than max_bytes (read no further than that: a device such as /dev/zero ends in the refusal).
std::string read_data(const DataRef& ref, std::size_t max_bytes = std::numeric_limits<std::size_t>::max());
//! Whether the file exists (built in, or a regular file on disk).
bool data_exists(const DataRef& ref);

}  // namespace stiffpath::core
