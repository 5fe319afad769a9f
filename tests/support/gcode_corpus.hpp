// Test helper: the malformed-program corpus (tests/data/gcode_bad/), each file's header giving its options and expected refusals.
#pragma once

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "stiffpath/motion/gcode_reader.hpp"

namespace stiffpath::test {

//! A corpus file's header: "; options: strict dwell-ms no-home" and one "; expect: LINE:COL: …"
//! line per refusal in file order, the file's path omitted; "; expect: … and N more" for the cap.
struct CorpusCase {
  std::filesystem::path path;
  std::vector<std::string> flags;     //!< the options as CLI flags, e.g. "--strict"
  motion::GcodeOptions options;
  std::vector<std::string> expected;  //!< each with the file's path in front
};

inline CorpusCase read_corpus_case(const std::filesystem::path& path) {
  CorpusCase c;
  c.path = path;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  for (bool first = true; std::getline(in, line); first = false) {
    if (first && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a byte-order mark
    if (line.rfind("; ", 0) != 0) break;
    if (line.rfind("; expect: ", 0) == 0) {
      const std::string rest = line.substr(10);
      c.expected.push_back(rest.rfind("… and ", 0) == 0 ? rest : path.string() + ":" + rest);
    } else if (line.rfind("; options: ", 0) == 0) {
      std::istringstream words(line.substr(11));
      for (std::string word; words >> word;) {
        if (word == "strict") {
          c.options.strict = true;
          c.flags.push_back("--strict");
        } else if (word == "dwell-ms") {
          c.options.dwell_p_units = motion::DwellUnits::milliseconds;
          c.flags.push_back("--dwell-p-units ms");
        } else if (word == "no-home") {  // a robot file without home_mm: G28 must be refused
          c.flags.push_back("--robot '" + (path.parent_path().parent_path() / "robots" / "oc-gu-no-home.json").string() + "'");
        } else {
          throw std::runtime_error(path.string() + ": unknown corpus option " + word);
        }
      }
    }
  }
  return c;
}

//! All corpus files, sorted by name.
inline std::vector<CorpusCase> read_corpus(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> paths;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == ".gcode") paths.push_back(entry.path());
  }
  std::sort(paths.begin(), paths.end());
  std::vector<CorpusCase> cases;
  for (const auto& path : paths) cases.push_back(read_corpus_case(path));
  return cases;
}

}  // namespace stiffpath::test
