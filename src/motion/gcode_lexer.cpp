// G-code lexer: words with columns, comments in (nested) parentheses or after ';', '%' delimiter lines.
#include "stiffpath/motion/gcode_lexer.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

namespace stiffpath::motion {

namespace {
constexpr std::size_t longest_shown = 24;  // characters of a number quoted in a message
}  // namespace

std::string word_name(const GcodeWord& word) {
  std::string name(1, word.letter);
  std::size_t shown = 0;
  for (const char c : word.number) {
    if (c == ' ' || c == '\t') continue;
    if (++shown > longest_shown) {
      name += "…";
      break;
    }
    name += c;
  }
  return name;
}

namespace {

[[noreturn]] void fail(const SourceLocation& where, std::size_t index, const std::string& message) {
  throw Error(SourceLocation{where.file, where.line, static_cast<int>(index) + 1}, message);
}

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }
bool letter(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }

// Reads the number after a letter at text[i...]; returns the index after it.
std::size_t read_number(std::string_view text, std::size_t i, const SourceLocation& where, std::size_t letter_at,
                        GcodeWord& word) {
  while (i < text.size() && blank(text[i])) ++i;
  const std::size_t begin = i;
  std::string compact;  // sign, digits and point without blanks or '+'
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
    if (text[i] == '-') compact += '-';
    ++i;
    while (i < text.size() && blank(text[i])) ++i;
  }
  int digits = 0, points = 0;
  bool whole_part_nonzero = false;  // a non-zero digit before the point: the value is at least 1
  std::size_t end = i;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.' || blank(text[i]))) {
    if (text[i] == '.') {
      if (++points > 1) break;
    } else if (!blank(text[i])) {
      ++digits;
      if (points == 0 && text[i] != '0') whole_part_nonzero = true;
    }
    if (!blank(text[i])) {
      compact += text[i];
      end = i + 1;
    }
    ++i;
  }
  word.letter = static_cast<char>(std::toupper(static_cast<unsigned char>(text[letter_at])));
  word.number = text.substr(begin, end - begin);
  if (digits == 0) fail(where, letter_at, std::string(1, word.letter) + ": a letter without a number");
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(compact.data(), compact.data() + compact.size(), value);
  if (ec == std::errc::result_out_of_range && !whole_part_nonzero) {
    value = 0.0;  // below the smallest double: zero for every purpose of a machine
  } else if (ec == std::errc::result_out_of_range) {
    fail(where, letter_at, word_name(word) + ": number too large");
  } else if (ec != std::errc() || ptr != compact.data() + compact.size() || !std::isfinite(value)) {
    fail(where, letter_at, word_name(word) + ": not a number");
  }
  word.value = value;
  return end;
}

// Index after the comment opened at text[open]; parentheses nest when `nested` is set.
std::size_t skip_comment(std::string_view text, std::size_t open, const SourceLocation& where, bool nested) {
  int depth = 0;
  for (std::size_t i = open; i < text.size(); ++i) {
    if (text[i] == '(') {
      if (depth > 0 && !nested) fail(where, i, "comments do not nest: '(' inside a comment");
      ++depth;
    } else if (text[i] == ')' && --depth == 0) {
      return i + 1;
    }
  }
  fail(where, open, "comment '(' is not closed on this line");
}

}  // namespace

bool lex_gcode_line(std::string_view text, const SourceLocation& where, std::vector<GcodeWord>& words,
                    bool nested_comments) {
  words.clear();
  std::size_t i = 0;
  while (i < text.size() && blank(text[i])) ++i;
  if (i < text.size() && text[i] == '%') return false;  // program start/end delimiter
  while (i < text.size()) {
    const char c = text[i];
    if (blank(c)) {
      ++i;
    } else if (c == '(') {
      i = skip_comment(text, i, where, nested_comments);
    } else if (c == ';') {
      break;
    } else if (letter(c)) {
      GcodeWord word;
      word.column = static_cast<int>(i) + 1;
      i = read_number(text, i + 1, where, i, word);
      if (word.letter == 'O') {  // "o100 sub", "o100 call": a keyword follows the number
        std::size_t k = i;
        while (k < text.size() && blank(text[k])) ++k;
        if (k + 1 < text.size() && letter(text[k]) && letter(text[k + 1])) {
          fail(where, static_cast<std::size_t>(word.column - 1),
               word_name(word) + ": subroutines and control flow (sub, call, if, while …) are not supported");
        }
      }
      words.push_back(word);
    } else {
      const bool printable = static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) < 0x7f;
      fail(where, i, printable ? std::string("unexpected character '") + c + "'" : "unexpected non-ASCII character");
    }
  }
  return true;
}

}  // namespace stiffpath::motion
