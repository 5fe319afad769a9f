// Header helpers shared by the measurement module's CSV loaders: located errors for missing columns and units.
#pragma once

#include <cstddef>
#include <string_view>

#include "stiffpath/core/csv.hpp"

namespace stiffpath::measurement {

//! 1-based character column of header field `index` (header names are unquoted).
int header_column(const core::CsvReader& csv, std::size_t index);

//! Index of a required column, or stiffpath::Error at file:header_line:1 naming the missing column,
//! the header found and the `expected` columns.
std::size_t require_column(const core::CsvReader& csv, std::string_view name, int header_line,
                           std::string_view expected);

//! Refuses a header column that carries `quantity` in a unit other than `unit` (e.g. quantity "Ux",
//! unit "mm" refuses "Ux_in"), with an Error at its header cell naming the column and the fix.
void require_unit(const core::CsvReader& csv, int header_line, std::string_view quantity, std::string_view unit);

}  // namespace stiffpath::measurement
