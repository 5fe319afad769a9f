# Sanitizer builds: ASan + UBSan for the CI's second pass (STIFFPATH_SANITIZE=ON), libFuzzer instrumentation
# for the fuzz harnesses (STIFFPATH_FUZZ=ON, clang), ThreadSanitizer for the threaded tests (STIFFPATH_TSAN=ON).
if(STIFFPATH_SANITIZE OR STIFFPATH_FUZZ)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
# -O1, as the sanitizers' authors advise: unoptimised Eigen under ASan made the twin's CLI tests 50-100x slower than
# the dev build's, which put the CI's time limit at risk. The sanitizer presets also debug with -g1 (line tables:
# reports keep file:line, the build is ~25 % faster than with -g).
if(STIFFPATH_SANITIZE OR STIFFPATH_FUZZ OR STIFFPATH_TSAN)
  add_compile_options(-O1)
endif()
if(STIFFPATH_FUZZ)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
if(STIFFPATH_TSAN)
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()
