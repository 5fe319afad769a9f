// Located header errors (missing column, wrong unit) for the measurement module's CSV loaders.
#include "stiffpath/measurement/csv_columns.hpp"

#include <fmt/format.h>

#include <string>

#include "stiffpath/core/error.hpp"

namespace stiffpath::measurement {

int header_column(const core::CsvReader& csv, std::size_t index) {
  int column = 1;
  for (std::size_t i = 0; i < index && i < csv.header().size(); ++i) {
    column += static_cast<int>(csv.header()[i].size()) + 1;
  }
  return column;
}

std::size_t require_column(const core::CsvReader& csv, std::string_view name, int header_line,
                           std::string_view expected) {
  if (auto index = csv.find_column(name)) return *index;
  std::string have;
  for (const auto& h : csv.header()) have += (have.empty() ? "" : ",") + h;
  throw Error(SourceLocation{csv.label(), header_line, 1},
              fmt::format("missing column '{}' (header: {}; expected {})", name, have, expected));
}

void require_unit(const core::CsvReader& csv, int header_line, std::string_view quantity, std::string_view unit) {
  for (std::size_t i = 0; i < csv.header().size(); ++i) {
    const std::string_view name = csv.header()[i];
    if (name.size() <= quantity.size() + 1 || !name.starts_with(quantity) || name[quantity.size()] != '_') continue;
    const std::string_view given = name.substr(quantity.size() + 1);
    if (given == unit) continue;
    throw Error(SourceLocation{csv.label(), header_line, header_column(csv, i)},
                fmt::format("column '{}': unit '{}' is not supported, use {}_{}", name, given, quantity, unit));
  }
}

}  // namespace stiffpath::measurement
