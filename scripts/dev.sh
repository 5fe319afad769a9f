#!/usr/bin/env bash
# One entry point for people and CI: bootstrap, build and then run the demo, the tests, the sanitizer tests or the benchmarks.
set -euo pipefail
cd "$(dirname "$0")/.."

what=${1:-demo}
jobs=$(nproc 2>/dev/null || echo 2)

bash scripts/bootstrap.sh

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
    build asan
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --preset asan
    ;;
  bench)
    build release
    for b in build/release/bench/bench_*; do "$b" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true; done
    ;;
  *)
    echo "usage: scripts/dev.sh demo|test|asan|bench" >&2
    exit 2
    ;;
esac
