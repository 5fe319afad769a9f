// Reading JSON documents with errors that name the file, the line and column, and the offending field.
#pragma once

#include <initializer_list>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>

namespace stiffpath::core {

//! Parses JSON text; a syntax error, a number beyond double range or a key given twice in one
//! object becomes stiffpath::Error "label:line:column: ...".
nlohmann::json parse_json(std::string_view text, const std::string& label);
//! Reads and parses a JSON file; errors name the path.
nlohmann::json read_json_file(const std::string& path);

//! Line and column (1-based) of every object key of a JSON text, by its path: "name",
//! "cg.label", "joints[1].min_deg" (and of every array element: "joints[1]"). The text must be
//! valid JSON (parse it first).
using JsonKeyIndex = std::map<std::string, std::pair<int, int>, std::less<>>;
JsonKeyIndex index_json_keys(std::string_view text);
//! As above, but refuses a key given twice in one object (label:line:column: DUPLICATE: ...).
JsonKeyIndex index_json_keys(std::string_view text, const std::string& label);

//! A parsed document with the positions of its keys, so that errors can point into the file.
struct JsonDocument {
  nlohmann::json value;
  std::string label;  //!< file path or another name for errors
  JsonKeyIndex keys;
};
//! Parses text (syntax errors as parse_json) and indexes its keys.
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
  JsonObject(const nlohmann::json& value, std::string label, std::string path, const JsonKeyIndex* keys);
  const nlohmann::json& field(std::string_view key) const;
  [[nodiscard]] std::string child_path(std::string_view key) const;

  const nlohmann::json& value_;
  std::string context_;               // bare mode: "<label>.<path>"
  std::string label_, path_;          // document mode
  const JsonKeyIndex* keys_ = nullptr;
};

}  // namespace stiffpath::core
