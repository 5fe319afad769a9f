// The shapes a scan is measured as, named in words ("line", "triangle", "polyline:N", "any"), for the CLI and the bindings.
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::vision {

ScanShape parse_scan_shape(const std::string& shape, const std::string& what) {
  if (shape == "line") return {1, evaluation::Closure::open};
  if (shape == "triangle") return {3, evaluation::Closure::closed};
  if (shape == "any") return {0, evaluation::Closure::automatic};
  if (shape.rfind("polyline:", 0) == 0) {
    const std::string n = shape.substr(9);
    if (!n.empty() && n.size() <= 2 && n.find_first_not_of("0123456789") == std::string::npos) {
      const int sides = std::stoi(n);
      if (sides >= 1 && sides <= 64) return {sides, evaluation::Closure::automatic};
    }
  }
  throw Error(fmt::format("{}: expected line, triangle, polyline:N with N in 1..64, or any, got '{}'", what, shape));
}

}  // namespace stiffpath::vision
