// Test helper: run a G-code text through GcodeReader and collect its segments.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "stiffpath/motion/gcode_reader.hpp"

namespace stiffpath::test {

inline std::vector<motion::PathSegment> read_gcode(const std::string& text, motion::GcodeOptions options = {}) {
  std::istringstream in(text);
  motion::GcodeReader reader(in, "job.gcode", options);
  std::vector<motion::PathSegment> segments;
  while (auto segment = reader.next()) segments.push_back(*segment);
  return segments;
}

//! The message of the Error the program raises, or "" if it reads without one.
inline std::string gcode_error(const std::string& text, motion::GcodeOptions options = {}) {
  try {
    read_gcode(text, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace stiffpath::test
