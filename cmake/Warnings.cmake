# Compiler warnings applied to every stiffpath target.
add_library(stiffpath_warnings INTERFACE)
target_compile_options(stiffpath_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion>)
