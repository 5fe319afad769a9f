# Compiler warnings applied to every stiffpath target.
add_library(stiffpath_warnings INTERFACE)
target_compile_options(stiffpath_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion>
  # GCC 12 reports false -Wrestrict overlaps inside std::string's operator+ at -O2/-O3 (GCC bug 105329).
  $<$<AND:$<CXX_COMPILER_ID:GNU>,$<VERSION_LESS:$<CXX_COMPILER_VERSION>,13>>:-Wno-restrict>)
