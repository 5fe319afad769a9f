// Data files compiled into the binary (mechanism presets, thesis tables), looked up by path under data/.
#pragma once

#include <optional>
#include <span>
#include <string_view>

namespace stiffpath::core {

struct EmbeddedFile {
  std::string_view path;     //!< relative to data/, e.g. "mechanisms/oc-gu.json"
  std::string_view content;  //!< the file's bytes
};

//! Every embedded file (generated at build time by cmake/EmbedFiles.cmake).
std::span<const EmbeddedFile> embedded_files() noexcept;
//! The content of an embedded file, or nullopt.
std::optional<std::string_view> find_embedded(std::string_view path) noexcept;

}  // namespace stiffpath::core
