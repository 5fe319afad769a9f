// stiffpath::Error and SourceLocation formatting.
#include "stiffpath/core/error.hpp"

namespace stiffpath {

// Built with append() rather than operator+ chains, which trip GCC 12's false -Wrestrict at -O3.
std::string SourceLocation::str() const {
  std::string out = file;
  if (line > 0) {
    out.append(":").append(std::to_string(line));
    if (column > 0) out.append(":").append(std::to_string(column));
  }
  return out;
}

namespace {
std::string compose(const SourceLocation& where, const std::string& message) {
  std::string out = where.str();
  if (out.empty()) return message;
  out.append(": ").append(message);
  return out;
}
}  // namespace

Error::Error(const std::string& message) : std::runtime_error(message), message_(message) {}

Error::Error(const SourceLocation& where, const std::string& message)
    : std::runtime_error(compose(where, message)), where_(where), message_(message) {}

}  // namespace stiffpath
