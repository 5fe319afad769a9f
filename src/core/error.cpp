// stiffpath::Error and SourceLocation formatting.
#include "stiffpath/core/error.hpp"

namespace stiffpath {

std::string SourceLocation::str() const {
  std::string out = file;
  if (line > 0) {
    out += ":" + std::to_string(line);
    if (column > 0) out += ":" + std::to_string(column);
  }
  return out;
}

namespace {
std::string compose(const SourceLocation& where, const std::string& message) {
  const std::string prefix = where.str();
  return prefix.empty() ? message : prefix + ": " + message;
}
}  // namespace

Error::Error(const std::string& message) : std::runtime_error(message), message_(message) {}

Error::Error(const SourceLocation& where, const std::string& message)
    : std::runtime_error(compose(where, message)), where_(where), message_(message) {}

}  // namespace stiffpath
