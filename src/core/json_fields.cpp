// JSON parsing and field access with errors that name the file and the field.
#include "stiffpath/core/json_fields.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "stiffpath/core/error.hpp"

namespace stiffpath::core {

namespace {
// Converts a byte offset into a 1-based line and column.
SourceLocation locate(std::string_view text, std::size_t byte, const std::string& label) {
  SourceLocation where{label, 1, 1};
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++where.line;
      where.column = 1;
    } else {
      ++where.column;
    }
  }
  return where;
}

std::string type_name(const nlohmann::json& v) { return v.type_name(); }
}  // namespace

nlohmann::json parse_json(std::string_view text, const std::string& label) {
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    const std::size_t byte = e.byte > 0 ? e.byte - 1 : 0;
    std::string message = e.what();
    if (auto pos = message.find("syntax error"); pos != std::string::npos) message = message.substr(pos);
    throw Error(locate(text, byte, label), "invalid JSON: " + message);
  }
}

nlohmann::json read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(SourceLocation{path}, "cannot open file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_json(buffer.str(), path);
}

JsonObject::JsonObject(const nlohmann::json& value, std::string context)
    : value_(value), context_(std::move(context)) {
  if (!value_.is_object()) throw Error(context_ + ": expected a JSON object, got " + type_name(value_));
}

bool JsonObject::has(std::string_view key) const { return value_.contains(key); }

void JsonObject::fail(std::string_view key, const std::string& message) const {
  throw Error(context_ + "." + std::string(key) + ": " + message);
}

const nlohmann::json& JsonObject::field(std::string_view key) const {
  const auto it = value_.find(key);
  if (it == value_.end()) fail(key, "missing field");
  return *it;
}

double JsonObject::number(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_number()) fail(key, "must be a number, got " + type_name(v) + " " + v.dump());
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(key, "must be finite");
  return x;
}

double JsonObject::positive(std::string_view key) const {
  const double x = number(key);
  if (!(x > 0.0)) fail(key, "must be positive, got " + field(key).dump());
  return x;
}

double JsonObject::non_negative(std::string_view key) const {
  const double x = number(key);
  if (x < 0.0) fail(key, "must not be negative, got " + field(key).dump());
  return x;
}

std::string JsonObject::string(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_string()) fail(key, "must be a string, got " + type_name(v) + " " + v.dump());
  return v.get<std::string>();
}

JsonObject JsonObject::object(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_object()) fail(key, "must be an object, got " + type_name(v));
  return JsonObject(v, context_ + "." + std::string(key));
}

const nlohmann::json& JsonObject::array(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_array()) fail(key, "must be an array, got " + type_name(v));
  return v;
}

}  // namespace stiffpath::core
