// Data references: resolving paths beside a robot file, built-in or on disk, and reading them.
#include "stiffpath/core/data_ref.hpp"

#include <array>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>

#include "stiffpath/core/embedded.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::core {

namespace {
constexpr std::string_view kBuiltinPrefix = "builtin:";
}

std::string DataRef::label() const { return builtin ? std::string(kBuiltinPrefix) + path : path; }

DataRef resolve_beside(const DataRef& base, const std::string& relative) {
  if (relative.starts_with(kBuiltinPrefix)) return parse_data_ref(relative);
  const std::filesystem::path rel(relative);
  if (rel.is_absolute()) return {rel.lexically_normal().string(), false};
  const std::filesystem::path joined = std::filesystem::path(base.path).parent_path() / rel;
  return {joined.lexically_normal().string(), base.builtin};
}

DataRef parse_data_ref(const std::string& text) {
  if (text.starts_with(kBuiltinPrefix)) return {text.substr(kBuiltinPrefix.size()), true};
  return {text, false};
}

std::string read_data(const DataRef& ref, std::size_t max_bytes) {
  const auto too_large = [&] {
    return Error(SourceLocation{ref.label()},
                 fmt::format("LIMIT: larger than {} bytes, the most a file of this kind may hold", max_bytes));
  };
  if (ref.builtin) {
    const auto text = find_embedded(ref.path);
    if (!text) throw Error(SourceLocation{ref.label()}, "no such file is built into this binary");
    if (text->size() > max_bytes) throw too_large();
    return std::string(*text);
  }
  std::ifstream in(ref.path, std::ios::binary);
  if (!in) throw Error(SourceLocation{ref.path}, "cannot open file");
  std::string out;
  std::array<char, 1 << 16> chunk{};
  while (in) {
    in.read(chunk.data(), chunk.size());
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got > max_bytes - out.size()) throw too_large();
    out.append(chunk.data(), got);
  }
  if (in.bad()) throw Error(SourceLocation{ref.path}, "read error");
  return out;
}

bool data_exists(const DataRef& ref) {
  if (ref.builtin) return find_embedded(ref.path).has_value();
  std::error_code ec;
  return std::filesystem::is_regular_file(ref.path, ec);
}

}  // namespace stiffpath::core
