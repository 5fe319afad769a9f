// stiffpath::Error: the one exception type of the library, carrying the input location (file:line:column).
#pragma once

#include <stdexcept>
#include <string>

namespace stiffpath {

//! Where in an input something went wrong. line/column are 1-based; 0 means "not known".
struct SourceLocation {
  std::string file;  //!< path as given by the user, or a label such as "<preset oc-gu>"
  int line = 0;
  int column = 0;

  //! "file:line:column", "file:line" or "file", omitting what is unknown.
  [[nodiscard]] std::string str() const;
};

//! Thrown by loaders, planners and checks for bad input. what() is "file:line:column: message".
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message);
  Error(const SourceLocation& where, const std::string& message);

  [[nodiscard]] const SourceLocation& where() const noexcept { return where_; }
  [[nodiscard]] const std::string& message() const noexcept { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

}  // namespace stiffpath
