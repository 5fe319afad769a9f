// One table per domain enum gives its names at the edges (CLI, JSON, bindings); one helper parses and prints them.
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "stiffpath/core/error.hpp"

namespace stiffpath::core {

//! Specialise for a domain enum, next to it, with
//!   static constexpr std::string_view what = "compensation method";   // for messages
//!   static constexpr std::array<std::pair<E, std::string_view>, N> names{{{E::a, "a"}, …}};
//! Inside the library the enum is the value; only the edges (command-line flags, files, bindings) see the names.
template <typename E>
struct EnumNames;

template <typename E>
concept NamedEnum = requires {
  EnumNames<E>::names;
  EnumNames<E>::what;
};

//! The name of `value` in its table ("" for a value the table lacks, which a complete table never has).
template <NamedEnum E>
constexpr std::string_view enum_name(E value) noexcept {
  for (const auto& [v, name] : EnumNames<E>::names) {
    if (v == value) return name;
  }
  return {};
}

//! The value named `text`, or nullopt.
template <NamedEnum E>
constexpr std::optional<E> find_enum(std::string_view text) noexcept {
  for (const auto& [v, name] : EnumNames<E>::names) {
    if (name == text) return v;
  }
  return std::nullopt;
}

//! The names in table order: "a, b or c".
template <NamedEnum E>
std::string enum_choices() {
  std::string out;
  const auto& names = EnumNames<E>::names;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += names[i].second;
  }
  return out;
}

//! The names in table order, e.g. for a command-line parser's list of choices.
template <NamedEnum E>
std::vector<std::string> enum_name_list() {
  std::vector<std::string> out;
  for (const auto& entry : EnumNames<E>::names) out.emplace_back(entry.second);
  return out;
}

//! The value named `text`; throws stiffpath::Error "<what> must be a, b or c, got 'text'".
template <NamedEnum E>
E parse_enum(std::string_view text) {
  if (const auto v = find_enum<E>(text)) return *v;
  throw Error(std::string(EnumNames<E>::what) + " must be " + enum_choices<E>() + ", got '" + std::string(text) + "'");
}

}  // namespace stiffpath::core
