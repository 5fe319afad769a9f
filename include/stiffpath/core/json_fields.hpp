// Reading JSON documents with errors that name the file and the offending field.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace stiffpath::core {

//! Parses JSON text; a syntax error becomes stiffpath::Error "label:line:column: ...".
nlohmann::json parse_json(std::string_view text, const std::string& label);
//! Reads and parses a JSON file; errors name the path.
nlohmann::json read_json_file(const std::string& path);

//! A view of one JSON object with the path that leads to it ("oc-gu.json: limits.joint1"), so that
//! every accessor can name the field it rejects.
class JsonObject {
 public:
  JsonObject(const nlohmann::json& value, std::string context);

  [[nodiscard]] bool has(std::string_view key) const;
  [[nodiscard]] const nlohmann::json& raw() const noexcept { return value_; }
  [[nodiscard]] const std::string& context() const noexcept { return context_; }

  [[nodiscard]] double number(std::string_view key) const;            //!< finite number
  [[nodiscard]] double positive(std::string_view key) const;          //!< finite, > 0
  [[nodiscard]] double non_negative(std::string_view key) const;      //!< finite, >= 0
  [[nodiscard]] std::string string(std::string_view key) const;
  [[nodiscard]] JsonObject object(std::string_view key) const;
  [[nodiscard]] const nlohmann::json& array(std::string_view key) const;

  //! Throws Error "<context>.<key>: message".
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

 private:
  const nlohmann::json& field(std::string_view key) const;
  const nlohmann::json& value_;
  std::string context_;
};

}  // namespace stiffpath::core
