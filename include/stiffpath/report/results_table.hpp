// A results table in the layout of thesis figs. 4.9–4.11: one row per robot × motion × acceleration × compensation.
#pragma once

#include <string>
#include <vector>

#include "stiffpath/simulation/experiment.hpp"

namespace stiffpath::report {

//! One run: what was marked and what was measured on the mark.
struct ResultRow {
  std::string robot;            //!< series name, e.g. "oc-gu"
  std::string motion;           //!< "x", "y", "triangle" or a user's path
  bool compensated = false;
  std::string variant;          //!< which compensation when compensated ("thesis", "default", a user's name; "" unnamed)
  double acceleration_g = 0.0;  //!< path acceleration limit (g)
  double length_mm = 0.0;       //!< measured length of the mark
  double deviation_area_mm2 = 0.0;  //!< area between the mark and its fitted line(s)
};

//! Rows and where they come from: `source` is "simulated" (the digital twin) or "measured" (scans of
//! real marks); figures say which in their titles.
struct ResultsTable {
  std::vector<ResultRow> rows;
  std::string source;
  std::string label;  //!< file name or "experiment", for titles and errors
};

//! The experiment's runs (source "simulated").
ResultsTable results_from_runs(const std::vector<simulation::RunResult>& results);

//! Reads a results CSV (docs/figures.md): columns robot, motion, compensated (0/1), acceleration_g,
//! length_mm, deviation_area_mm2 by header name, other columns ignored; `variant` as an optional column
//! naming the compensation of compensated rows (each variant is its own series; ignored on rows without
//! compensation); `source` as an optional column (the same value, simulated or measured, on every row). `source_flag` ("" when not given) must agree with
//! the column when both exist; with neither the table is refused, so that no figure guesses its provenance.
//! Errors name the file, line and column (stiffpath::Error).
ResultsTable load_results_csv(const std::string& path, const std::string& source_flag = "");

//! "simulated" | "measured"; throws stiffpath::Error otherwise.
std::string check_source(const std::string& text);

}  // namespace stiffpath::report
