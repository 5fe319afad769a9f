// The core module in one include: errors with their place, units, CSV and JSON readers with their bounds, atomic outputs, enums' names, least squares.
#pragma once

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/core/enum_names.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/core/data_ref.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/atomic_directory.hpp"
#include "stiffpath/core/distinct_files.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/core/least_squares.hpp"
#include "stiffpath/core/median.hpp"
