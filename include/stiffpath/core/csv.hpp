// Streaming CSV reader with header lookup and file:line:column errors for every bad cell.
#pragma once

#include <cstddef>
#include <fstream>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stiffpath/core/error.hpp"

namespace stiffpath::core {

//! Largest magnitude a CSV number may have (1e12): beyond any time, length, force or angle in our
//! files, in their units, and small enough that sums of squares in the fits stay finite.
inline constexpr double max_csv_magnitude = 1e12;
//! Longest CSV line (64 KiB; our files' lines hold a few hundred bytes): a longer one is refused at
//! its line before it is read whole.
inline constexpr std::size_t max_csv_line_bytes = 64U << 10U;

//! Most data rows a table read whole into memory may hold (displacement tables, campaigns,
//! repeatability trials): 10^6 rows, about 0.6 GB once read; the thesis's table has 600.
inline constexpr std::size_t max_table_rows = 1'000'000;
//! Most bytes of such a table when it is read whole before parsing (256 MiB: 10^6 rows of 256 bytes).
inline constexpr std::size_t max_table_bytes = 256U << 20U;

//! Whether `text` is valid UTF-8 (no overlong forms, surrogates or code points beyond U+10FFFF).
[[nodiscard]] bool valid_utf8(std::string_view text) noexcept;

//! Reads a comma-separated file row by row (so files need not fit in memory). The first non-comment
//! line is the header. Lines starting with '#' and blank lines are skipped. Fields may be quoted
//! with double quotes. Every accessor that rejects a cell throws stiffpath::Error naming the file,
//! line, column and the offending text.
class CsvReader {
 public:
  //! Opens a file; throws Error("<path>: cannot open") if it cannot.
  explicit CsvReader(const std::string& path);
  //! Reads from a stream; `label` names it in errors.
  CsvReader(std::istream& in, std::string label);

  [[nodiscard]] const std::vector<std::string>& header() const noexcept { return header_; }
  [[nodiscard]] const std::string& label() const noexcept { return label_; }
  //! Index of a header column, or an error naming the missing column and the header line.
  [[nodiscard]] std::size_t column(std::string_view name) const;
  [[nodiscard]] std::optional<std::size_t> find_column(std::string_view name) const;

  //! Advances to the next data row; false at the end of input. A row whose field count differs from
  //! the header's is an error.
  bool next();
  [[nodiscard]] int line() const noexcept { return line_; }
  [[nodiscard]] std::size_t size() const noexcept { return fields_.size(); }

  [[nodiscard]] std::string_view text(std::size_t col) const;
  //! Text that names something (a point, a mechanism): valid UTF-8, since names go into JSON
  //! files; an error at the cell otherwise.
  [[nodiscard]] std::string_view name(std::size_t col) const;
  //! A finite number within ±max_csv_magnitude; empty cells, NaN, inf, 1e300 and trailing garbage
  //! are errors ("file:line:column: column 'x_mm': RANGE: ...").
  [[nodiscard]] double number(std::size_t col) const;
  //! A finite number, or nullopt for an empty cell (a "missing" value).
  [[nodiscard]] std::optional<double> optional_number(std::size_t col) const;
  [[nodiscard]] long integer(std::size_t col) const;
  //! Location of a cell, for errors raised by callers ("value out of range" etc.).
  [[nodiscard]] SourceLocation where(std::size_t col) const;
  [[nodiscard]] SourceLocation where() const { return SourceLocation{label_, line_, 0}; }
  //! Throws Error at the cell with "column 'name': message".
  [[noreturn]] void fail(std::size_t col, const std::string& message) const;

 private:
  bool read_line();  // into buffer_, at most max_csv_line_bytes
  bool read_record(std::vector<std::string>& fields, std::vector<int>& starts);

  std::unique_ptr<std::ifstream> owned_;
  std::istream* in_;
  std::string label_;
  std::vector<std::string> header_;
  std::vector<std::string> fields_;
  std::vector<int> starts_;  // 1-based character column of each field
  std::string buffer_;
  std::vector<char> line_buffer_;  // max_csv_line_bytes + 2 bytes, for istream::getline
  int line_ = 0;
  int header_line_ = 1;  // after leading comments and blank lines
};

//! Parses a finite double from the whole of `text` (no trailing characters); nullopt otherwise.
std::optional<double> parse_double(std::string_view text) noexcept;

}  // namespace stiffpath::core
