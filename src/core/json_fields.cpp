// JSON parsing and field access with errors that name the file and the field.
#include "stiffpath/core/json_fields.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "stiffpath/core/error.hpp"

namespace stiffpath::core {

namespace {
// Largest magnitude of a number field (number() and what builds on it), as for CSV files (csv.hpp).
constexpr double max_json_magnitude = 1e12;

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

namespace {
// Parses without the duplicate-key check. A number beyond double's range (1e400) is refused at its position.
nlohmann::json parse_only(std::string_view text, const std::string& label) {
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    const std::size_t byte = e.byte > 0 ? e.byte - 1 : 0;
    std::string message = e.what();
    if (auto pos = message.find("syntax error"); pos != std::string::npos) message = message.substr(pos);
    throw Error(locate(text, byte, label), "invalid JSON: " + message);
  } catch (const nlohmann::json::out_of_range& e) {
    std::string message = e.what();
    std::size_t byte = 0;
    const auto open = message.find('\'');
    const auto close = open == std::string::npos ? open : message.find('\'', open + 1);
    if (close != std::string::npos) {
      const std::string token = message.substr(open + 1, close - open - 1);
      if (const auto at = text.find(token); at != std::string_view::npos) byte = at;
      message = "RANGE: number " + token + " is beyond the range of a double (about 1.8e308)";
    }
    throw Error(locate(text, byte, label), "invalid JSON: " + message);
  }
}
}  // namespace

nlohmann::json parse_json(std::string_view text, const std::string& label) {
  nlohmann::json value = parse_only(text, label);
  (void)index_json_keys(text, label);  // refuses duplicated keys
  return value;
}

nlohmann::json read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(SourceLocation{path}, "cannot open file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_json(buffer.str(), path);
}

JsonDocument parse_json_document(std::string_view text, const std::string& label) {
  JsonDocument doc{parse_only(text, label), label, {}};
  doc.keys = index_json_keys(text, label);
  return doc;
}

JsonDocument read_json_document(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(SourceLocation{path}, "cannot open file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_json_document(buffer.str(), path);
}

JsonObject::JsonObject(const nlohmann::json& value, std::string context)
    : value_(value), context_(std::move(context)) {
  if (!value_.is_object()) throw Error(context_ + ": expected a JSON object, got " + type_name(value_));
}

JsonObject::JsonObject(const JsonDocument& document) : JsonObject(document.value, document.label, "", &document.keys) {}

JsonObject::JsonObject(const nlohmann::json& value, std::string label, std::string path, const JsonKeyIndex* keys)
    : value_(value), context_(path.empty() ? label : label + "." + path), label_(std::move(label)),
      path_(std::move(path)), keys_(keys) {
  if (!value_.is_object()) {
    const auto it = keys_->find(path_);
    const SourceLocation where =
        it == keys_->end() ? SourceLocation{label_} : SourceLocation{label_, it->second.first, it->second.second};
    throw Error(where, (path_.empty() ? std::string("document") : path_) + ": expected a JSON object, got " +
                           type_name(value_));
  }
}

std::string JsonObject::child_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

bool JsonObject::has(std::string_view key) const { return value_.contains(key); }

void JsonObject::fail(std::string_view key, const std::string& message) const {
  if (!keys_) throw Error(context_ + "." + std::string(key) + ": " + message);
  const std::string path = child_path(key);
  auto it = keys_->find(path);
  if (it == keys_->end()) it = keys_->find(path_);  // a missing field: point at its object
  const SourceLocation where =
      it == keys_->end() ? SourceLocation{label_} : SourceLocation{label_, it->second.first, it->second.second};
  throw Error(where, path + ": " + message);
}

void JsonObject::allow_only(std::initializer_list<std::string_view> known,
                            const std::map<std::string, std::string, std::less<>>& hints) const {
  std::string first;
  std::pair<int, int> first_at{1 << 30, 0};
  for (const auto& item : value_.items()) {
    bool ok = false;
    for (const auto k : known) ok = ok || item.key() == k;
    if (ok) continue;
    std::pair<int, int> at{1 << 29, 0};
    if (keys_) {
      if (const auto it = keys_->find(child_path(item.key())); it != keys_->end()) at = it->second;
    }
    if (first.empty() || at < first_at) {
      first = item.key();
      first_at = at;
    }
  }
  if (first.empty()) return;
  const auto hint = hints.find(first);
  fail(first, "unknown field" + (hint == hints.end() ? std::string() : " (" + hint->second + ")"));
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
  if (std::abs(x) > max_json_magnitude) fail(key, "RANGE: " + v.dump() + " is beyond ±1e12, larger than any quantity a stiffpath file holds");
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

int JsonObject::sign(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_number() || (v.get<double>() != 1.0 && v.get<double>() != -1.0)) fail(key, "must be +1 or -1, got " + v.dump());
  return v.get<double>() > 0 ? 1 : -1;
}

std::pair<double, double> JsonObject::pair(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
    fail(key, "must be an array of two numbers [a, b], got " + v.dump());
  }
  const double a = v[0].get<double>(), b = v[1].get<double>();
  if (!std::isfinite(a) || !std::isfinite(b)) fail(key, "must hold finite numbers");
  return {a, b};
}

std::string JsonObject::string(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_string()) fail(key, "must be a string, got " + type_name(v) + " " + v.dump());
  return v.get<std::string>();
}

JsonObject JsonObject::object(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_object()) fail(key, "must be an object, got " + type_name(v));
  if (keys_) return JsonObject(v, label_, child_path(key), keys_);
  return JsonObject(v, context_ + "." + std::string(key));
}

const nlohmann::json& JsonObject::array(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_array()) fail(key, "must be an array, got " + type_name(v));
  return v;
}

JsonObject JsonObject::element(std::string_view key, std::size_t index) const {
  const auto& a = array(key);
  const std::string name = std::string(key) + "[" + std::to_string(index) + "]";
  if (index >= a.size()) fail(key, "has no element " + std::to_string(index));
  if (!a[index].is_object()) fail(name, "must be an object, got " + type_name(a[index]));
  if (keys_) return JsonObject(a[index], label_, child_path(name), keys_);
  return JsonObject(a[index], context_ + "." + name);
}

}  // namespace stiffpath::core
