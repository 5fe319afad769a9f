// What `run` prints about a finished job: its settings as resolved (model, method, filters) and its peaks.
#pragma once

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "stiffpath/job/prepared_job.hpp"

namespace stiffpath::cli {

//! The summary as JSON (keys with units; `filters` names every reference filter applied, or "none").
nlohmann::json job_summary_json(const job::PreparedJob& job, const job::JobSummary& summary, const std::string& output);
//! The summary as text on `out`.
void print_job_summary(std::FILE* out, const job::PreparedJob& job, const job::JobSummary& summary,
                       const std::string& output);

}  // namespace stiffpath::cli
