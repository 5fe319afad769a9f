// G-code lexer: words with columns, comments in parentheses or after ';', '%' delimiter lines.
#include "stiffpath/motion/gcode_lexer.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

namespace stiffpath::motion {

std::string word_name(const GcodeWord& word) {
  std::string name(1, word.letter);
  for (const char c : word.number) {
    if (c != ' ' && c != '\t') name += c;
  }
  return name;
}

namespace {

[[noreturn]] void fail(const SourceLocation& where, std::size_t index, const std::string& message) {
  throw Error(SourceLocation{where.file, where.line, static_cast<int>(index) + 1}, message);
}

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

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
  std::size_t end = i;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.' || blank(text[i]))) {
    if (text[i] == '.') {
      if (++points > 1) break;
    } else if (!blank(text[i])) {
      ++digits;
    }
    if (!blank(text[i])) {
      compact += text[i];
      end = i + 1;
    }
    ++i;
  }
  const std::string letter(1, static_cast<char>(std::toupper(static_cast<unsigned char>(text[letter_at]))));
  if (digits == 0) fail(where, letter_at, letter + ": a letter without a number");
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(compact.data(), compact.data() + compact.size(), value);
  if (ec != std::errc() || ptr != compact.data() + compact.size() || !std::isfinite(value)) {
    fail(where, letter_at, letter + std::string(text.substr(begin, end - begin)) + ": not a number");
  }
  word.value = value;
  word.number = text.substr(begin, end - begin);
  return end;
}

}  // namespace

bool lex_gcode_line(std::string_view text, const SourceLocation& where, std::vector<GcodeWord>& words) {
  words.clear();
  std::size_t i = 0;
  while (i < text.size() && blank(text[i])) ++i;
  if (i < text.size() && text[i] == '%') return false;  // program start/end delimiter
  while (i < text.size()) {
    const char c = text[i];
    if (blank(c)) {
      ++i;
    } else if (c == '(') {
      const std::size_t close = text.find(')', i + 1);
      if (close == std::string_view::npos) fail(where, i, "comment '(' is not closed on this line");
      i = close + 1;
    } else if (c == ';') {
      break;
    } else if (std::isalpha(static_cast<unsigned char>(c))) {
      GcodeWord word;
      word.letter = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      word.column = static_cast<int>(i) + 1;
      i = read_number(text, i + 1, where, i, word);
      words.push_back(word);
    } else {
      const bool printable = static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) < 0x7f;
      fail(where, i, printable ? std::string("unexpected character '") + c + "'" : "unexpected non-ASCII character");
    }
  }
  return true;
}

}  // namespace stiffpath::motion
