// JSON parsing and field access with errors that name the file and the field.
#include "stiffpath/core/json_fields.hpp"

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "json_walk.hpp"
#include "stiffpath/core/data_ref.hpp"
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

std::string shown(const nlohmann::json& v) {
  std::string text = v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);  // bad UTF-8 as U+FFFD
  if (text.size() > 80) {
    std::size_t cut = 77;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U) --cut;  // not inside a character
    text = text.substr(0, cut) + "...";
  }
  return text;
}

namespace {
// Parses without the duplicate-key check. A number beyond double's range (1e400) is refused at its position.
nlohmann::json parse_only(std::string_view text, const std::string& label) {
  check_json_shape(text, label);
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
  check_json_duplicates(text, label);
  return value;
}

nlohmann::json read_json_file(const std::string& path) {
  return parse_json(read_data(DataRef{path, false}, max_json_bytes), path);
}

JsonDocument parse_json_document(std::string_view text, const std::string& label) {
  JsonDocument doc{parse_only(text, label), label, std::string(text)};
  check_json_duplicates(text, label);
  return doc;
}

JsonDocument read_json_document(const std::string& path) {
  return parse_json_document(read_data(DataRef{path, false}, max_json_bytes), path);
}

JsonObject::JsonObject(const nlohmann::json& value, std::string context)
    : value_(value), context_(std::move(context)) {
  if (!value_.is_object()) throw Error(context_ + ": expected a JSON object, got " + type_name(value_));
}

JsonObject::JsonObject(const JsonDocument& document) : JsonObject(document.value, document.label, "", &document.text) {}

JsonObject::JsonObject(const nlohmann::json& value, std::string label, std::string path, const std::string* text)
    : value_(value), context_(path.empty() ? label : label + "." + path), label_(std::move(label)),
      path_(std::move(path)), text_(text) {
  if (!value_.is_object()) {
    throw Error(where(path_), (path_.empty() ? std::string("document") : path_) + ": expected a JSON object, got " +
                                  type_name(value_));
  }
}

SourceLocation JsonObject::where(const std::string& path) const {
  // The root has no key of its own: what concerns it names the file alone.
  if (path.empty()) return SourceLocation{label_};
  const auto at = locate_json_path(*text_, path);
  return at ? SourceLocation{label_, at->first, at->second} : SourceLocation{label_};
}

std::string JsonObject::child_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

bool JsonObject::has(std::string_view key) const { return value_.contains(key); }

void JsonObject::fail(std::string_view key, const std::string& message) const {
  if (!text_) throw Error(context_ + "." + std::string(key) + ": " + message);
  const std::string path = child_path(key);
  // A present field at its key; a missing one at the object that lacks it.
  SourceLocation at = where(path);
  if (at.line == 0) at = where(path_);  // a missing field: at the object that lacks it
  throw Error(at, path + ": " + message);
}

void JsonObject::allow_only(std::initializer_list<std::string_view> known,
                            const std::map<std::string, std::string, std::less<>>& hints) const {
  const auto is_known = [&](std::string_view key) {
    for (const auto k : known) {
      if (key == k) return true;
    }
    return false;
  };
  std::string first;
  for (const auto& item : value_.items()) {
    if (!is_known(item.key())) {
      first = item.key();  // alphabetically first; the file's order decides below when the text is known
      break;
    }
  }
  if (first.empty()) return;
  if (text_) {
    for (const auto& member : json_object_members(*text_, path_)) {
      if (!is_known(member.key)) {
        first = member.key;
        break;
      }
    }
  }
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
  if (!v.is_number()) fail(key, "must be a number, got " + type_name(v) + " " + shown(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(key, "must be finite");
  if (std::abs(x) > max_json_magnitude) fail(key, "RANGE: " + shown(v) + " is beyond ±1e12, larger than any quantity a stiffpath file holds");
  return x;
}

double JsonObject::positive(std::string_view key) const {
  const double x = number(key);
  if (!(x > 0.0)) fail(key, "must be positive, got " + shown(field(key)));
  return x;
}

double JsonObject::non_negative(std::string_view key) const {
  const double x = number(key);
  if (x < 0.0) fail(key, "must not be negative, got " + shown(field(key)));
  return x;
}

double JsonObject::within(std::string_view key, double lo, double hi, std::string_view unit) const {
  const double x = number(key);
  if (!(x >= lo && x <= hi)) {
    fail(key, fmt::format("RANGE: {} {} is outside the physical range {:g} to {:g} {}", shown(field(key)), unit, lo, hi, unit));
  }
  return x;
}

int JsonObject::sign(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_number() || (v.get<double>() != 1.0 && v.get<double>() != -1.0)) fail(key, "must be +1 or -1, got " + shown(v));
  return v.get<double>() > 0 ? 1 : -1;
}

std::pair<double, double> JsonObject::pair(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
    fail(key, "must be an array of two numbers [a, b], got " + shown(v));
  }
  const double a = v[0].get<double>(), b = v[1].get<double>();
  if (!std::isfinite(a) || !std::isfinite(b)) fail(key, "must hold finite numbers");
  return {a, b};
}

std::string JsonObject::string(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_string()) fail(key, "must be a string, got " + type_name(v) + " " + shown(v));
  return v.get<std::string>();
}

JsonObject JsonObject::object(std::string_view key) const {
  const auto& v = field(key);
  if (!v.is_object()) fail(key, "must be an object, got " + type_name(v));
  if (text_) return JsonObject(v, label_, child_path(key), text_);
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
  if (text_) return JsonObject(a[index], label_, child_path(name), text_);
  return JsonObject(a[index], context_ + "." + name);
}

}  // namespace stiffpath::core
