#!/usr/bin/env bash
# Writes the thesis presets' reference results (joint-file hashes, experiment, cv, kin, predict, simulate) with one binary.
# The files in tests/data/regression/ were made by this script with the binary built from commit bd69b46
# (before robots became general); tests/cli/test_cli_thesis_regression.cpp checks the current build against them.
# The joint-file hashes of gear_outline and nameplate were rewritten later, when joining runs changed their plans.
# Usage: scripts/make_thesis_regression.sh STIFFPATH [OUT_DIR]
set -eu
bin=$(realpath "$1") out=${2:-$(dirname "$0")/../tests/data/regression}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
out=$(realpath "$out")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
# Joint files: one line "<example> <variant> <sha256 of the joint file>" per run at 5 g.
variants=("bin|--format bin" "csv|--format csv" "sc-gl|--format bin --mechanism sc-gl"
          "oc-gl|--format bin --mechanism oc-gl" "physical|--format bin --model thesis-oc-physical"
          "numeric|--format bin --accel-source numeric" "gain|--format bin --gain 0.8"
          "plain|--format bin --no-compensation")
: > "$out/joint_hashes.txt"
for job in "$here"/examples/*.gcode; do
  name=$(basename "$job" .gcode)
  for v in "${variants[@]}"; do
    tag=${v%%|*} flags=${v#*|}
    # shellcheck disable=SC2086
    "$bin" run "$job" --accel 5g $flags -o "$work/j" > /dev/null
    echo "$name $tag $(sha256sum "$work/j" | cut -d' ' -f1)" >> "$out/joint_hashes.txt"
  done
done
# The twin: the y motion compensated and not, through simulate.
"$bin" run "$here/examples/y_motion.gcode" --accel 5g --format bin -o y.bin > /dev/null
"$bin" simulate y.bin --json > "$out/simulate_y_oc-gu.json"
"$bin" run "$here/examples/triangle.gcode" --accel 3g --format bin --mechanism sc-gu --no-compensation -o t.bin > /dev/null
"$bin" simulate t.bin --sides 3 --mechanism sc-gu --json > "$out/simulate_triangle_sc-gu_plain.json"
# The thesis's 120-run test matrix.
"$bin" experiment -o exp --no-plots > /dev/null
cp exp/results.csv "$out/experiment_results.csv"
# Cross-validation, kinematics on the grid, predictions.
"$bin" cv thesis --mechanism oc-gu --json > "$out/cv_oc.json"
"$bin" cv thesis --mechanism sc-gu --json > "$out/cv_sc.json"
"$bin" kin grid --json > "$out/kin_grid.json"
for m in thesis-oc thesis-sc-physical; do
  "$bin" predict --model $m --x-mm 240.5 --y-mm -20.25 --fx-n 180 --fy-n -95 --json > "$out/predict_$m.json"
done
echo "wrote $out"
