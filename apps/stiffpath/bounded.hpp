// A CLI11 check for numeric options: finite and within documented bounds, refused as "--option: reason".
#pragma once

#include <CLI/CLI.hpp>

namespace stiffpath::cli {

//! Accepts a number in [low, high] (NaN and ±inf fail); the refusal reads
//! "--flag: must be within [low, high] unit, got value". Each value of a multi-value option is checked.
CLI::Validator within(double low, double high, const char* unit);

//! Accepts a non-empty output name: "-o ''" would write nothing and say nothing, so it is refused.
CLI::Validator output_name();

}  // namespace stiffpath::cli
