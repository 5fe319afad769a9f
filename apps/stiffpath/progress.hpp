// A progress bar on stderr for commands that take a while: drawn only on a terminal, never with --quiet.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <string_view>

#include "stiffpath/job/job.hpp"

namespace stiffpath::cli {

//! Shows "label [#####     ]  42%  note" on one line of stderr, redrawn in place. It draws nothing
//! when stderr is not a terminal or `quiet` is set, and nothing until the work has run for half a
//! second (STIFFPATH_PROGRESS_DELAY_S overrides that delay, e.g. 0 to always draw), so scripts and
//! quick runs see no trace of it. The line is cleared when the work ends.
class Progress {
 public:
  Progress(std::string label, bool quiet);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  //! The fraction done (clamped to 0..1) and an optional note; redraws at most ten times a second.
  void update(double fraction, std::string_view note = {});
  //! Clears the line (also done by the destructor).
  void finish();
  //! Whether it can draw at all (a terminal and not quiet).
  [[nodiscard]] bool enabled() const noexcept { return enabled_; }
  //! update() as a callback for library functions that report the fraction done.
  [[nodiscard]] std::function<void(double)> callback();

 private:
  std::string label_;
  bool enabled_ = false, drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
  double delay_s_ = 0.5;
};

//! A job's progress on `bar` as the share of the G-code file's lines done; empty when the bar cannot draw.
[[nodiscard]] job::Progress job_progress(const std::string& gcode_file, Progress& bar);

}  // namespace stiffpath::cli
