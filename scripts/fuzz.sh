#!/usr/bin/env bash
# Runs every libFuzzer harness of a fuzz build for a bounded time, seeded from the project's data; prints executions.
# usage: scripts/fuzz.sh BUILD_DIR SECONDS_PER_HARNESS [HARNESS...]   (default: all harnesses)
# FUZZ_RUNS=N stops each harness after N executions instead (SECONDS stays the cap).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?build dir, e.g. build/fuzz}
seconds=${2:-20}
shift 2 || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(gcode csv displacement_table campaign repeatability joint_file robot_json model_json image_metadata plate c_robot c_model)

# Seed folders per harness: the shipped data, the test inputs and the malformed-input corpus.
seeds() {
  case "$1" in
    gcode) echo examples tests/data/cam tests/data/gcode_bad tests/data/bad/gcode ;;
    csv) echo data/thesis tests/data/bad/displacement_table tests/data/bad/campaign tests/data/bad/repeatability ;;
    displacement_table) echo data/thesis tests/data/bad/displacement_table ;;
    campaign) echo tests/data/fuzz_seeds/campaign tests/data/bad/campaign ;;
    repeatability) echo data/thesis tests/data/bad/repeatability ;;
    joint_file) echo tests/data/fuzz_seeds/joint_file tests/data/bad/joints ;;
    robot_json) echo data/robots tests/data/robots tests/data/bad/robot ;;
    model_json|c_model) echo tests/data/fuzz_seeds/model_json tests/data/bad/model ;;
    c_robot) echo data/robots tests/data/robots tests/data/bad/robot ;;
    image_metadata) echo tests/data/fuzz_seeds/image_metadata tests/data/fuzz_regressions/image_metadata tests/data/bad/image ;;
    plate) echo examples/plates tests/data/fuzz_seeds/plate tests/data/bad/plate ;;
    calibration_plate) echo tests/data/fuzz_seeds/calibration_plate tests/data/bad/calibration_plate ;;
  esac
}

# The file-reading harnesses write every input to a file: on a tmpfs that costs ~10× less than on disk. A private
# folder, removed at the end (and on Ctrl-C), so no input file stays behind.
base=${TMPDIR:-/tmp}
if [ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ]; then base=/dev/shm; fi
TMPDIR=$(mktemp -d "$base/stiffpath-fuzz.XXXXXX")
export TMPDIR
trap 'rm -rf "$TMPDIR"' EXIT
runs=()
[ -z "${FUZZ_RUNS:-}" ] || runs=(-runs="$FUZZ_RUNS")

mkdir -p "$build/findings"
status=0
for h in "${harnesses[@]}"; do
  corpus="$build/corpus/$h"
  mkdir -p "$corpus"
  dirs=()
  for d in $(seeds "$h"); do [ -d "$d" ] && dirs+=("$d"); done
  log="$build/findings/$h.log"
  set +e
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/fuzz/fuzz_$h" -max_total_time="$seconds" "${runs[@]}" -max_len=8192 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/findings/$h-" "$corpus" "${dirs[@]}" >"$log" 2>&1
  rc=$?
  set -e
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  if [ $rc -eq 0 ]; then
    took=$(grep -o 'Done [0-9]* runs in [0-9]* second' "$log" | grep -o 'in [0-9]*' | grep -o '[0-9]*' || echo "$seconds")
    echo "fuzz_$h: ${execs} executions in ${took} s, corpus $(ls "$corpus" | wc -l) inputs, no finding"
  else
    echo "fuzz_$h: FINDING (exit $rc) after ${execs} executions; see $log and $build/findings/$h-*" >&2
    grep -m5 -E 'ERROR|runtime error|SUMMARY|terminate' "$log" >&2 || true
    status=1
  fi
done
exit $status
