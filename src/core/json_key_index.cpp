// Positions of the keys of a JSON text, so that a field's error can name its line and column.
#include <cctype>
#include <optional>
#include <string>

#include "stiffpath/core/error.hpp"

#include "stiffpath/core/json_fields.hpp"

namespace stiffpath::core {

namespace {
// A recursive walk over valid JSON that tracks line and column.
class KeyScanner {
 public:
  KeyScanner(std::string_view text, JsonKeyIndex& index) : text_(text), index_(index) {}

  struct Duplicate {
    std::string path;
    int line, column;
  };
  //! The first key that appeared twice in one object, if any.
  std::optional<Duplicate> duplicate_;

  void value(const std::string& path) {
    skip_space();
    if (at_end()) return;
    const char c = text_[pos_];
    if (c == '{') {
      object(path);
    } else if (c == '[') {
      array(path);
    } else if (c == '"') {
      (void)string_token();
    } else {
      while (!at_end() && text_[pos_] != ',' && text_[pos_] != '}' && text_[pos_] != ']' &&
             !std::isspace(static_cast<unsigned char>(text_[pos_]))) {
        advance();
      }
    }
  }

 private:
  void object(const std::string& path) {
    advance();  // {
    for (;;) {
      skip_space();
      if (at_end() || text_[pos_] == '}') break;
      if (text_[pos_] == ',') {
        advance();
        continue;
      }
      const int line = line_, column = column_;
      const std::string raw = string_token();
      std::string key = raw;
      try {
        key = nlohmann::json::parse("\"" + raw + "\"").get<std::string>();
      } catch (const nlohmann::json::exception&) {
      }
      const std::string child = path.empty() ? key : path + "." + key;
      if (!index_.emplace(child, std::make_pair(line, column)).second && !duplicate_) {
        duplicate_ = Duplicate{child, line, column};
      }
      skip_space();
      if (!at_end() && text_[pos_] == ':') advance();
      value(child);
    }
    if (!at_end()) advance();  // }
  }

  void array(const std::string& path) {
    advance();  // [
    std::size_t index = 0;
    for (;;) {
      skip_space();
      if (at_end() || text_[pos_] == ']') break;
      if (text_[pos_] == ',') {
        advance();
        ++index;
        continue;
      }
      const std::string child = path + "[" + std::to_string(index) + "]";
      index_.emplace(child, std::make_pair(line_, column_));
      value(child);
    }
    if (!at_end()) advance();  // ]
  }

  // The raw characters between the quotes (escapes kept), the position left after the closing quote.
  std::string string_token() {
    advance();  // opening quote
    std::string out;
    while (!at_end() && text_[pos_] != '"') {
      if (text_[pos_] == '\\' && pos_ + 1 < text_.size()) {
        out += text_[pos_];
        advance();
      }
      out += text_[pos_];
      advance();
    }
    if (!at_end()) advance();  // closing quote
    return out;
  }

  void skip_space() {
    while (!at_end() && std::isspace(static_cast<unsigned char>(text_[pos_]))) advance();
  }
  [[nodiscard]] bool at_end() const { return pos_ >= text_.size(); }
  void advance() {
    if (text_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    ++pos_;
  }

  std::string_view text_;
  JsonKeyIndex& index_;
  std::size_t pos_ = 0;
  int line_ = 1, column_ = 1;
};
}  // namespace

JsonKeyIndex index_json_keys(std::string_view text) {
  JsonKeyIndex index;
  KeyScanner(text, index).value("");
  return index;
}

JsonKeyIndex index_json_keys(std::string_view text, const std::string& label) {
  JsonKeyIndex index;
  KeyScanner scanner(text, index);
  scanner.value("");
  if (const auto& d = scanner.duplicate_) {
    throw Error(SourceLocation{label, d->line, d->column},
                "DUPLICATE: key '" + d->path + "' appears twice in one object (which one is meant is ambiguous)");
  }
  return index;
}

}  // namespace stiffpath::core
