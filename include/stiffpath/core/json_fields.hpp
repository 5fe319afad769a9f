// Reading JSON documents with errors that name the file, the line and column, and the offending field.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "stiffpath/core/error.hpp"

namespace stiffpath::core {

//! What a JSON file may hold (robot, model and plate files need a few kB and six levels): larger or
//! deeper text is refused before it is parsed, at the byte or bracket that crosses the limit.
inline constexpr std::size_t max_json_bytes = 8U << 20U;  //!< 8 MiB
inline constexpr int max_json_depth = 64;                 //!< nested objects and arrays

//! Parses JSON text; a syntax error, a number beyond double range, a key given twice in one
//! object, text beyond max_json_bytes or nesting beyond max_json_depth becomes stiffpath::Error
//! "label:line:column: ...".
nlohmann::json parse_json(std::string_view text, const std::string& label);
//! Reads (at most max_json_bytes) and parses a JSON file; errors name the path.
nlohmann::json read_json_file(const std::string& path);

//! Line and column (1-based) of the key (or array element) at `path` in JSON text: "name",
//! "cg.label", "joints[1].min_deg", "joints[1]"; nothing when there is no such key. The text must
//! be valid JSON within the limits above (parse it first). One pass over the text, no recursion.
std::optional<std::pair<int, int>> locate_json_path(std::string_view text, std::string_view path);
//! The keys of the object at `path` ("" for the root) with their line and column, in file order.
struct JsonMember {
  std::string key;
  int line = 0, column = 0;
};
std::vector<JsonMember> json_object_members(std::string_view text, std::string_view path);

//! A value as a message shows it: its JSON text (bad UTF-8 as U+FFFD), cut after 80 characters.
std::string shown(const nlohmann::json& v);

//! A parsed document with its text, so that errors can point into the file.
struct JsonDocument {
  nlohmann::json value;
  std::string label;  //!< file path or another name for errors
  std::string text;   //!< the text it was parsed from
};
//! Parses text (errors as parse_json).
JsonDocument parse_json_document(std::string_view text, const std::string& label);
//! Reads and parses a file into a JsonDocument.
JsonDocument read_json_document(const std::string& path);

//! A view of one JSON object with the path that leads to it, so that every accessor can name the
//! field it rejects. Made from a JsonDocument, errors read "file:line:column: path.key: message"
//! (the key's own position); made from a bare value and a context, "<context>.<key>: message".
class JsonObject {
 public:
  JsonObject(const nlohmann::json& value, std::string context);
  //! The document's root object.
  explicit JsonObject(const JsonDocument& document);

  [[nodiscard]] bool has(std::string_view key) const;
  [[nodiscard]] const nlohmann::json& raw() const noexcept { return value_; }
  [[nodiscard]] const std::string& context() const noexcept { return context_; }
  //! The path of this object inside its document ("" for the root, "joints[1]").
  [[nodiscard]] const std::string& path() const noexcept { return path_; }

  [[nodiscard]] double number(std::string_view key) const;            //!< finite number
  [[nodiscard]] double positive(std::string_view key) const;          //!< finite, > 0
  [[nodiscard]] double non_negative(std::string_view key) const;      //!< finite, >= 0
  //! A finite number within [lo, hi] (a physical range, in the key's unit), else "RANGE: …".
  [[nodiscard]] double within(std::string_view key, double lo, double hi, std::string_view unit) const;
  [[nodiscard]] int sign(std::string_view key) const;                 //!< +1 or −1
  [[nodiscard]] std::pair<double, double> pair(std::string_view key) const;  //!< [a, b] of finite numbers
  [[nodiscard]] std::string string(std::string_view key) const;
  [[nodiscard]] JsonObject object(std::string_view key) const;
  [[nodiscard]] const nlohmann::json& array(std::string_view key) const;
  //! Element `index` of the array `key`, which must be an object.
  [[nodiscard]] JsonObject element(std::string_view key, std::size_t index) const;

  //! Refuses any key not in `known`: the first such key in the file (by position when known) as
  //! "<where>: key: unknown field" + `hint` when the key has one.
  void allow_only(std::initializer_list<std::string_view> known,
                  const std::map<std::string, std::string, std::less<>>& hints = {}) const;

  //! Throws Error naming the field (and its position when known): "<where>: key: message".
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

 private:
  JsonObject(const nlohmann::json& value, std::string label, std::string path, const std::string* text);
  [[nodiscard]] SourceLocation where(const std::string& path) const;
  const nlohmann::json& field(std::string_view key) const;
  [[nodiscard]] std::string child_path(std::string_view key) const;

  const nlohmann::json& value_;
  std::string context_;               // bare mode: "<label>.<path>"
  std::string label_, path_;          // document mode
  const std::string* text_ = nullptr;  // document mode: the text, for positions
};

}  // namespace stiffpath::core
