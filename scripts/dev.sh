#!/usr/bin/env bash
# One entry point for people and CI: bootstrap, build and then run the demo, the tests, the sanitizer tests, the fuzzers or the benchmarks.
set -euo pipefail
cd "$(dirname "$0")/.."

what=${1:-demo}
jobs=$(nproc 2>/dev/null || echo 2)

case "$what" in
  linuxcnc|bindings|browser) bash scripts/bootstrap.sh "$what" ;;
  *) bash scripts/bootstrap.sh ;;
esac

build() {  # build <preset>
  cmake --preset "$1" >/dev/null
  cmake --build --preset "$1" -j "$jobs"
}

case "$what" in
  demo)
    build dev
    bash scripts/demo.sh build/dev/bin/stiffpath
    ;;
  test)
    build dev
    ctest --preset dev
    ;;
  asan)
    # Every test program but the command line's and the browser's (the CLI's own tests spawn the program: under the
    # unoptimised ASan build they cost more than all the rest; the dev suite runs them), with the library and the C
    # interface under AddressSanitizer + UBSan. STIFFPATH_ASAN_ALL=1 builds and runs everything.
    cmake --preset asan >/dev/null
    if [ "${STIFFPATH_ASAN_ALL:-0}" = 1 ]; then
      cmake --build --preset asan -j "$jobs"
      ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --preset asan
    else
      mapfile -t targets < <(ninja -C build/asan -t targets all | sed -n 's/^\(test_[a-z_]*\): phony$/\1/p' |
                              grep -v -x -e test_cli -e test_browser | sort -u)
      cmake --build --preset asan -j "$jobs" --target "${targets[@]}"
      ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        ctest --preset asan -L '^(core|kinematics|compliance|measurement|motion|compensation|job|simulation|evaluation|calibration|vision|c_api)$'
    fi
    ;;
  bench)
    build release
    for b in build/release/bench/bench_*; do "$b" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true; done
    ;;
  fuzz)
    # Every libFuzzer harness (fuzz/) for FUZZ_SECONDS (default 20) each under ASan + UBSan, seeded from
    # tests/data and data/; new corpus entries stay in build/fuzz/corpus, findings in build/fuzz/findings.
    cmake --preset fuzz >/dev/null
    cmake --build --preset fuzz -j "$jobs" --target fuzz_all
    bash scripts/fuzz.sh build/fuzz "${FUZZ_SECONDS:-20}"
    ;;
  tsan)
    # The threaded tests (the job's two-thread pipeline) under ThreadSanitizer; only their target is built.
    cmake --preset tsan >/dev/null
    cmake --build --preset tsan -j "$jobs" --target test_job
    TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 ctest --preset tsan -L job
    ;;
  linuxcnc)
    # The C interface and the LinuxCNC integration: modules built and copied into LinuxCNC's module
    # directory (root), then the tests labelled c_api and linuxcnc (LinuxCNC runs headless, see docs/linuxcnc.md).
    cmake --preset dev -DSTIFFPATH_LINUXCNC=ON >/dev/null
    cmake --build --preset dev -j "$jobs" --target stiffpath_cli stiffpath_halstream stiffpath_linuxcnc_modules \
      check_gcode_record test_stiffpath_c test_c_api
    # The modules also build with CMake's default generator (Unix Makefiles), as a plain `cmake -S . -B build` does: their
    # custom command runs in a folder the configure step must create (Makefiles do not, Ninja does). CI configures a
    # Makefiles tree and checks that folder; building its modules there compiles the whole library a second time
    # (minutes of CI), so that build runs only with STIFFPATH_MAKEFILES_BUILD=1 (docs/linuxcnc.md).
    launcher=()
    command -v ccache >/dev/null && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
    cmake -S . -B build/make -G "Unix Makefiles" -DSTIFFPATH_LINUXCNC=ON -DSTIFFPATH_BUILD_TESTS=OFF \
      -DSTIFFPATH_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG" \
      "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG" "${launcher[@]}" >/dev/null
    if grep -q "stiffpath_linuxcnc_modules" build/make/Makefile 2>/dev/null; then
      [ -d build/make/integrations/linuxcnc/modules ] ||
        { echo "dev.sh linuxcnc: the Makefiles tree lacks integrations/linuxcnc/modules" >&2; exit 1; }
    fi
    if [ "${STIFFPATH_MAKEFILES_BUILD:-0}" = 1 ]; then
      CCACHE_NOHASHDIR=1 cmake --build build/make -j "$jobs" --target stiffpath_linuxcnc_modules
    fi
    sudo_cmd=()
    [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
    "${sudo_cmd[@]}" cmake --build --preset dev --target stiffpath_linuxcnc_install_modules
    ctest --preset dev -L 'c_api|linuxcnc'
    ;;
  bindings)
    # The Python module (pytest) and the MATLAB/Octave gateway (an Octave script), both against the CLI's numbers.
    cmake --preset dev -DSTIFFPATH_BUILD_PYTHON=ON -DSTIFFPATH_BUILD_MATLAB=ON >/dev/null
    cmake --build --preset dev -j "$jobs"
    for label in python octave; do  # asked for by name: missing tools are an error here, not a skipped test
      ctest --preset dev -N -L "$label" | grep -q 'Total Tests: [1-9]' ||
        { echo "dev.sh bindings: no $label tests configured (see the configure messages)" >&2; exit 1; }
    done
    ctest --preset dev -L 'python|octave|install'
    ;;
  browser)
    # The HTML report in headless Chromium (the test labelled browser; it cannot skip here).
    cmake --preset dev >/dev/null
    cmake --build --preset dev -j "$jobs" --target stiffpath_cli test_browser
    STIFFPATH_REQUIRE_BROWSER=1 ctest --preset dev -L browser
    ;;
  *)
    echo "usage: scripts/dev.sh demo|test|asan|bench|linuxcnc|bindings|browser|fuzz|tsan" >&2
    exit 2
    ;;
esac
