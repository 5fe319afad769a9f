// One pass over JSON text without recursion: its size and depth, keys given twice, and where a key sits.
#include <cctype>
#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "json_walk.hpp"

namespace stiffpath::core {

namespace {
// A key with its escapes resolved ("esc\"aped" -> esc"aped); raw when the escapes are not valid.
std::string decode_key(std::string_view raw) {
  if (raw.find('\\') == std::string_view::npos) return std::string(raw);
  try {
    return nlohmann::json::parse("\"" + std::string(raw) + "\"").get<std::string>();
  } catch (const nlohmann::json::exception&) {
    return std::string(raw);
  }
}

// Walks valid JSON with an explicit stack, calling visit(path, line, column) at every object key and
// array element in file order ("cg.label", "joints[1]"); visit returns false to stop. The path lives
// in one buffer that grows and shrinks with the nesting, so the walk costs time and memory linear in
// the text whatever its shape. With check_duplicates, the first key given twice in one object is kept.
class Walker {
 public:
  Walker(std::string_view text, std::string_view target, bool check_duplicates)
      : text_(text), target_(target), check_duplicates_(check_duplicates) {}

  struct Duplicate {
    std::string path;
    int line, column;
  };
  std::optional<Duplicate> duplicate;

  // visit(path, line, column, at_target, member_of_target): at_target when path equals the target
  // given above, member_of_target when it is a key of the object at the target.
  template <class Visit>
  void run(Visit&& visit) {
    skip_space();
    if (at_end()) return;
    open_value(target_.empty());
    while (!stack_.empty()) {
      skip_space();
      if (at_end()) return;
      Frame& top = stack_.back();
      const char c = text_[pos_];
      if (c == ',') {
        advance();
        if (top.array) ++top.index;
        continue;
      }
      if (c == '}' || c == ']') {
        advance();
        stack_.pop_back();
        continue;
      }
      const int line = line_, column = column_;
      set_length(top.base);
      if (top.array) {
        append("[" + std::to_string(top.index) + "]");
      } else {
        const std::string key = decode_key(string_token());
        append(path_.empty() ? key : "." + key);
        if (check_duplicates_ && !top.keys.insert(key).second && !duplicate) {
          duplicate = Duplicate{path_, line, column};
        }
        skip_space();
        if (!at_end() && text_[pos_] == ':') advance();
        skip_space();
        if (at_end()) return;
      }
      const bool at_target = matched_ == path_.size() && matched_ == target_.size();
      if (!visit(std::string_view(path_), line, column, at_target, top.is_target && !top.array)) return;
      open_value(at_target);
    }
  }

 private:
  struct Frame {
    bool array = false;
    std::size_t base = 0;   // length of the container's own path
    std::size_t index = 0;  // current element of an array
    bool is_target = false;  // its path is the target
    std::set<std::string> keys;  // of this object only: "a.b" here and "b" inside "a" are different keys
  };

  // At the start of a value: a container opens a frame, a string or a scalar is skipped.
  void open_value(bool is_target) {
    const char c = text_[pos_];
    if (c == '{' || c == '[') {
      advance();
      stack_.push_back(Frame{c == '[', path_.size(), 0, is_target, {}});
    } else if (c == '"') {
      (void)string_token();
    } else {
      while (!at_end() && text_[pos_] != ',' && text_[pos_] != '}' && text_[pos_] != ']' &&
             !std::isspace(static_cast<unsigned char>(text_[pos_]))) {
        advance();
      }
    }
  }

  // The path buffer and how much of it equals the target's beginning, kept up to date as it changes.
  void set_length(std::size_t n) {
    path_.resize(n);
    if (matched_ > n) matched_ = n;
  }
  void append(const std::string& part) {
    const std::size_t start = path_.size();
    path_ += part;
    if (matched_ != start) return;
    while (matched_ < path_.size() && matched_ < target_.size() && path_[matched_] == target_[matched_]) ++matched_;
  }

  // The raw characters between the quotes (escapes kept); the position is left after the closing quote.
  std::string_view string_token() {
    advance();  // opening quote
    const std::size_t start = pos_;
    while (!at_end() && text_[pos_] != '"') {
      if (text_[pos_] == '\\' && pos_ + 1 < text_.size()) advance();
      advance();
    }
    const std::string_view raw = text_.substr(start, pos_ - start);
    if (!at_end()) advance();  // closing quote
    return raw;
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

  std::string_view text_, target_;
  bool check_duplicates_;
  std::vector<Frame> stack_;
  std::string path_;
  std::size_t matched_ = 0;
  std::size_t pos_ = 0;
  int line_ = 1, column_ = 1;
};
}  // namespace

void check_json_shape(std::string_view text, const std::string& label) {
  if (text.size() > max_json_bytes) {
    throw Error(SourceLocation{label},
                fmt::format("LIMIT: {} bytes, more than the {} bytes (8 MiB) a JSON file may hold", text.size(),
                            max_json_bytes));
  }
  int depth = 0, line = 1, column = 1;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
        ++column;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      if (++depth > max_json_depth) {
        throw Error(SourceLocation{label, line, column},
                    fmt::format("LIMIT: nested more than {} levels deep (objects and arrays)", max_json_depth));
      }
    } else if (c == '}' || c == ']') {
      --depth;
    }
    if (c == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

void check_json_duplicates(std::string_view text, const std::string& label) {
  Walker walker(text, {}, true);
  walker.run([](std::string_view, int, int, bool, bool) { return true; });
  if (const auto& d = walker.duplicate) {
    throw Error(SourceLocation{label, d->line, d->column},
                "DUPLICATE: key '" + d->path + "' appears twice in one object (which one is meant is ambiguous)");
  }
}

std::optional<std::pair<int, int>> locate_json_path(std::string_view text, std::string_view path) {
  std::optional<std::pair<int, int>> found;
  Walker(text, path, false).run([&](std::string_view, int line, int column, bool at_target, bool) {
    if (at_target) found = std::make_pair(line, column);
    return !at_target;
  });
  return found;
}

std::vector<JsonMember> json_object_members(std::string_view text, std::string_view path) {
  std::vector<JsonMember> members;
  // A member's path is the object's path, a dot (none at the root), and its key.
  const std::size_t skip = path.empty() ? 0 : path.size() + 1;
  Walker(text, path, false).run([&](std::string_view p, int line, int column, bool, bool member) {
    if (member) {
      members.push_back(JsonMember{std::string(p.substr(skip)), line, column});
    }
    return true;
  });
  return members;
}

}  // namespace stiffpath::core
