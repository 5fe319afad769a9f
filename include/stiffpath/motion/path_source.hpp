// The pull interface of the motion pipeline's path stages (G-code reader, corner blender).
#pragma once

#include <optional>

#include "stiffpath/motion/path_segment.hpp"

namespace stiffpath::motion {

//! Something that hands out path segments one at a time, in program order; nullopt at the end.
//! Stages pull from the stage before them, so no stage needs the whole program in memory.
class PathSource {
 public:
  virtual ~PathSource() = default;
  virtual std::optional<PathSegment> next() = 0;
};

}  // namespace stiffpath::motion
