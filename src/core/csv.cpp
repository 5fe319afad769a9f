// CsvReader: streaming CSV parsing with precise error locations.
#include "stiffpath/core/csv.hpp"

#include <charconv>
#include <cstdint>
#include <cmath>

namespace stiffpath::core {

std::optional<double> parse_double(std::string_view text) noexcept {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

bool valid_utf8(std::string_view text) noexcept {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t n = 0;
    std::uint32_t cp = 0, min = 0;
    if ((c & 0xE0U) == 0xC0U) {
      n = 1, cp = c & 0x1FU, min = 0x80;
    } else if ((c & 0xF0U) == 0xE0U) {
      n = 2, cp = c & 0x0FU, min = 0x800;
    } else if ((c & 0xF8U) == 0xF0U) {
      n = 3, cp = c & 0x07U, min = 0x10000;
    } else {
      return false;
    }
    if (i + n >= text.size()) return false;
    for (std::size_t k = 1; k <= n; ++k) {
      const auto d = static_cast<unsigned char>(text[i + k]);
      if ((d & 0xC0U) != 0x80U) return false;
      cp = (cp << 6U) | (d & 0x3FU);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += n + 1;
  }
  return true;
}

namespace {
// A column named twice makes every lookup by name ambiguous: refuse it at the second occurrence.
void refuse_duplicate_columns(const std::vector<std::string>& header, const std::vector<int>& starts,
                              const std::string& label, int line) {
  for (std::size_t i = 1; i < header.size(); ++i) {
    if (header[i].empty()) continue;
    for (std::size_t k = 0; k < i; ++k) {
      if (header[k] != header[i]) continue;
      throw Error(SourceLocation{label, line, i < starts.size() ? starts[i] : 1},
                  "DUPLICATE: column '" + header[i] + "' appears twice in the header (columns " + std::to_string(k + 1) +
                      " and " + std::to_string(i + 1) + ")");
    }
  }
}
}  // namespace

CsvReader::CsvReader(const std::string& path)
    : owned_(std::make_unique<std::ifstream>(path, std::ios::binary)), in_(owned_.get()), label_(path) {
  if (!*owned_) throw Error(SourceLocation{path}, "cannot open file");
  std::vector<int> starts;
  if (!read_record(header_, starts)) throw Error(SourceLocation{path}, "file is empty (no header line)");
  header_line_ = line_;
  refuse_duplicate_columns(header_, starts, label_, header_line_);
}

CsvReader::CsvReader(std::istream& in, std::string label) : in_(&in), label_(std::move(label)) {
  std::vector<int> starts;
  if (!read_record(header_, starts)) throw Error(SourceLocation{label_}, "input is empty (no header line)");
  header_line_ = line_;
  refuse_duplicate_columns(header_, starts, label_, header_line_);
}

bool CsvReader::read_line() {
  if (line_buffer_.empty()) line_buffer_.resize(max_csv_line_bytes + 2);
  in_->getline(line_buffer_.data(), static_cast<std::streamsize>(line_buffer_.size()));
  const auto got = static_cast<std::size_t>(in_->gcount());
  if (in_->fail() && !in_->eof()) {  // a full buffer and no line break yet
    throw Error(SourceLocation{label_, line_ + 1, 1},
                "LIMIT: line longer than " + std::to_string(max_csv_line_bytes) + " bytes, the most a CSV line may hold");
  }
  if (got == 0 && in_->eof()) return false;
  const bool ended_by_break = !in_->eof();  // getline counted the line break it extracted
  buffer_.assign(line_buffer_.data(), ended_by_break ? got - 1 : got);
  in_->clear(in_->rdstate() & ~std::ios::failbit);
  return true;
}

bool CsvReader::read_record(std::vector<std::string>& fields, std::vector<int>& starts) {
  while (read_line()) {
    ++line_;
    if (!buffer_.empty() && buffer_.back() == '\r') buffer_.pop_back();
    if (buffer_.find_first_not_of(" \t") == std::string::npos || buffer_.front() == '#') continue;
    fields.clear();
    starts.clear();
    std::string field;
    bool quoted = false;
    int start = 1;
    for (std::size_t i = 0; i < buffer_.size(); ++i) {
      const char c = buffer_[i];
      if (quoted) {
        if (c == '"' && i + 1 < buffer_.size() && buffer_[i + 1] == '"') {
          field += '"';
          ++i;
        } else if (c == '"') {
          quoted = false;
        } else {
          field += c;
        }
      } else if (c == '"') {
        quoted = true;
      } else if (c == ',') {
        fields.push_back(std::move(field));
        starts.push_back(start);
        field.clear();
        start = static_cast<int>(i) + 2;
      } else {
        field += c;
      }
    }
    if (quoted) throw Error(SourceLocation{label_, line_, start}, "unterminated quoted field");
    fields.push_back(std::move(field));
    starts.push_back(start);
    for (auto& f : fields) {
      while (!f.empty() && (f.back() == ' ' || f.back() == '\t')) f.pop_back();
      std::size_t lead = 0;
      while (lead < f.size() && (f[lead] == ' ' || f[lead] == '\t')) ++lead;
      f.erase(0, lead);
    }
    return true;
  }
  return false;
}

std::optional<std::size_t> CsvReader::find_column(std::string_view name) const {
  for (std::size_t i = 0; i < header_.size(); ++i) {
    if (header_[i] == name) return i;
  }
  return std::nullopt;
}

std::size_t CsvReader::column(std::string_view name) const {
  if (auto index = find_column(name)) return *index;
  std::string have;
  for (const auto& h : header_) have += (have.empty() ? "" : ", ") + h;
  throw Error(SourceLocation{label_, header_line_}, "missing column '" + std::string(name) + "' (header has: " + have + ")");
}

bool CsvReader::next() {
  if (!read_record(fields_, starts_)) return false;
  if (fields_.size() != header_.size()) {
    throw Error(SourceLocation{label_, line_},
                "row has " + std::to_string(fields_.size()) + " fields, the header has " +
                    std::to_string(header_.size()));
  }
  return true;
}

SourceLocation CsvReader::where(std::size_t col) const {
  return SourceLocation{label_, line_, col < starts_.size() ? starts_[col] : 0};
}

void CsvReader::fail(std::size_t col, const std::string& message) const {
  const std::string name = col < header_.size() ? header_[col] : "#" + std::to_string(col + 1);
  throw Error(where(col), "column '" + name + "': " + message);
}

std::string_view CsvReader::text(std::size_t col) const {
  if (col >= fields_.size()) fail(col, "no such column in this row");
  return fields_[col];
}

std::string_view CsvReader::name(std::size_t col) const {
  const std::string_view cell = text(col);
  if (!valid_utf8(cell)) fail(col, "the name is not valid UTF-8 text (names go into JSON files)");
  return cell;
}

double CsvReader::number(std::size_t col) const {
  const std::string_view cell = text(col);
  if (cell.empty()) fail(col, "value is missing (empty cell)");
  if (auto value = parse_double(cell)) {
    if (std::abs(*value) > max_csv_magnitude) {
      fail(col, "RANGE: " + std::string(cell) + " is beyond ±1e12, larger than any quantity a stiffpath file holds");
    }
    return *value;
  }
  fail(col, "'" + std::string(cell) + "' is not a finite number");
}

std::optional<double> CsvReader::optional_number(std::size_t col) const {
  if (text(col).empty()) return std::nullopt;
  return number(col);
}

long CsvReader::integer(std::size_t col) const {
  const std::string_view cell = text(col);
  long value = 0;
  const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (cell.empty() || ec != std::errc() || end != cell.data() + cell.size()) {
    fail(col, "'" + std::string(cell) + "' is not an integer");
  }
  return value;
}

}  // namespace stiffpath::core
