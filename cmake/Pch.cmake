# Precompiled headers: the third-party and standard headers nearly every file includes, parsed once per target.
# Parsing them is 30-50 % of a file's compile time (Eigen, nlohmann/json, fmt); a fresh build (CI, a new machine)
# pays it once per target instead of once per file. Off when a compiler launcher such as ccache is set: ccache cannot
# cache files compiled against a precompiled header without extra settings, and it already avoids the recompiles.
if(CMAKE_CXX_COMPILER_LAUNCHER)
  set(stiffpath_pch_default OFF)
else()
  set(stiffpath_pch_default ON)
endif()
option(STIFFPATH_PCH "Precompile the common headers (default: on unless a compiler launcher such as ccache is set)"
       ${stiffpath_pch_default})

set(stiffpath_pch_headers string vector Eigen/Core nlohmann/json.hpp fmt/format.h)

# stiffpath_precompile(<target> [extra headers…]): the common headers, plus the target's own heavy ones (gtest, CLI11).
# C++ only, so targets with C sources keep compiling them as they are.
function(stiffpath_precompile target)
  if(NOT STIFFPATH_PCH)
    return()
  endif()
  set(headers)
  foreach(h IN LISTS stiffpath_pch_headers ARGN)
    list(APPEND headers "$<$<COMPILE_LANGUAGE:CXX>:<${h}$<ANGLE-R>>")
  endforeach()
  target_precompile_headers(${target} PRIVATE ${headers})
endfunction()
