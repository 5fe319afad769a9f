#!/usr/bin/env bash
# Runs `stiffpath run` with a reference and a candidate binary on every example at 5 g and compares the joint files.
# A job that leaves the workspace checks that refusals keep their message.
# Usage: scripts/run_equivalence.sh REFERENCE_STIFFPATH CANDIDATE_STIFFPATH [WORK_DIR]
# Variants: bilinear (bin, csv), numeric acceleration, physical model, gain 0.8, no compensation,
# extrapolation outside the grid, the SC build. A refused job must be
# refused with the same message; the JSON summaries must be identical.
set -u
ref=$1 cand=$2 work=${3:-$(mktemp -d)}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$work"
variants=("bin|--format bin" "csv|--format csv" "numeric|--format bin --accel-source numeric"
          "physical|--format bin --model thesis-oc-physical" "gain|--format bin --gain 0.8"
          "plain|--format bin --no-compensation" "extrapolate|--format bin --outside extrapolate"
          "sc|--format bin --mechanism sc-gl")
failed=0
printf 'G21 G90\nG0 X222 Y0\nM3 S100\nG1 X296 F60000\nM5\n' > "$work/far.gcode"  # refused: out of reach
for job in "$here"/examples/*.gcode "$work/far.gcode"; do
  name=$(basename "$job" .gcode)
  for v in "${variants[@]}"; do
    tag=${v%%|*} flags=${v#*|}
    for who in ref cand; do
      bin=$ref; [ $who = cand ] && bin=$cand
      # shellcheck disable=SC2086
      "$bin" run "$job" --accel 5g $flags -o "$work/$name.$tag.$who" --json > "$work/$name.$tag.$who.json" \
        2> "$work/$name.$tag.$who.err"
      echo $? > "$work/$name.$tag.$who.rc"
    done
    echo "$name $tag (exit $(cat "$work/$name.$tag.ref.rc"))"
    if ! cmp -s "$work/$name.$tag.ref.rc" "$work/$name.$tag.cand.rc" ||
       ! cmp -s "$work/$name.$tag.ref.err" "$work/$name.$tag.cand.err"; then
      echo "  exit status or error message differs"; failed=1; continue
    fi
    # Numbers only: the output path and the names of the robot and its model may differ between builds.
    keys='"output"|"mechanism"|"robot"|"model"'
    if ! diff -q <(grep -Ev "$keys" "$work/$name.$tag.ref.json") <(grep -Ev "$keys" "$work/$name.$tag.cand.json") \
         > /dev/null; then
      echo "  JSON summary differs"; failed=1
    fi
    if [ -f "$work/$name.$tag.ref" ]; then
      python3 "$here/scripts/compare_joints.py" "$work/$name.$tag.ref" "$work/$name.$tag.cand" || failed=1
    fi
  done
done
[ $failed = 0 ] && echo "all equivalent" || echo "DIFFERENCES FOUND"
exit $failed
