// Splitting one G-code line into words (letter + number), dropping comments, with the column of each word.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "stiffpath/core/error.hpp"

namespace stiffpath::motion {

//! One word of a block, e.g. "G1", "x-10.5", "F3000".
struct GcodeWord {
  char letter = 0;          //!< upper case
  double value = 0.0;       //!< the number as written, in program units
  int column = 0;           //!< 1-based column of the letter
  std::string_view number;  //!< the number's text (a view into the line)
};

//! The word as written with its letter in upper case: "G41", "X10.5" (numbers over 24 characters
//! are shortened with "…").
std::string word_name(const GcodeWord& word);

//! Splits `text` (one line without its newline) into words. Comments in parentheses and after ';'
//! are dropped; with `nested_comments` parentheses nest, "(a (nested) comment)", otherwise a '('
//! inside a comment is refused. Spaces may appear anywhere between words and inside a word
//! ("G 1", "X -5"); upper or lower case. Numbers are decimal without exponent; one whose value
//! overflows a double is refused, one that underflows reads as 0. Returns false for a '%' program
//! delimiter line (its words are empty). Throws stiffpath::Error at `where` (file and line; the
//! column is filled in) for an unclosed comment, a letter without a number, an O word with a
//! keyword (subroutines, control flow), or any other character.
bool lex_gcode_line(std::string_view text, const SourceLocation& where, std::vector<GcodeWord>& words,
                    bool nested_comments = true);

}  // namespace stiffpath::motion
