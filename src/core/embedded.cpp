// Lookup of embedded data files by path.
#include "stiffpath/core/embedded.hpp"

namespace stiffpath::core {

std::optional<std::string_view> find_embedded(std::string_view path) noexcept {
  for (const auto& file : embedded_files()) {
    if (file.path == path) return file.content;
  }
  return std::nullopt;
}

}  // namespace stiffpath::core
