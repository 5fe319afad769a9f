#!/usr/bin/env bash
# Accuracy sweeps of `stiffpath scan` on rendered scans against their truth: lines, lines with wiggling starts, the twin's triangles.
# Usage: scripts/scan_accuracy.sh [stiffpath] [cases] [texture] [noise] [lines|wiggles|twin]
#   (defaults: build/dev/bin/stiffpath 40 0.01 0.01 lines)
#   lines:   100 / 150 mm lines at seeded random angles in [-3°, 3°]
#   wiggles: 150 mm lines whose start vibrates, A·e^(-s/30 mm)·sin(2πs/λ) with seeded A in [0.05, 1] mm
#            and λ in [3, 15] mm, kept to paths leaving their start at up to 46° (atan 2πA/λ)
#   twin:    the digital twin's triangle (examples/triangle.gcode) on OC G_U and SC G_L at 1, 3 and 5 g,
#            with and without compensation (cases is ignored): run -> simulate -> render-scan -> scan
set -euo pipefail
stiffpath=$(realpath "${1:-build/dev/bin/stiffpath}")
cases=${2:-40}
texture=${3:-0.01}
noise=${4:-0.01}
mode=${5:-lines}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

summary() {  # label: reads $work/truth_*.json and $work/scan_*.json pairs listed in $work/cases
  python3 - "$work" "$1" "$texture" "$noise" <<'PY'
import json, math, sys
work, label, texture, noise = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
err, refused, warned = [], [], 0
for name in open(f"{work}/cases").read().split():
    t = json.load(open(f"{work}/truth_{name}.json"))
    try:
        s = json.load(open(f"{work}/scan_{name}.json"))
    except (json.JSONDecodeError, FileNotFoundError):
        refused.append(f"{name}: " + open(f"{work}/err_{name}.txt").read().strip())
        continue
    err.append((s["length_mm"] - t["length_mm"]) * 1000)
    warned += 1 if s["warnings"] else 0
    for w in s["warnings"]:
        print(f"  case {name} ({err[-1]:+.2f} um) warns: {w}")
    if label == "twin":
        print(f"  {name}: truth {t['length_mm']:.4f} mm, scan - truth {err[-1]:+.2f} um, warnings {len(s['warnings'])}")
n = len(err)
if n:
    rms = math.sqrt(sum(e * e for e in err) / n)
    print(f"{label}: {n} measured, texture {texture}, noise {noise}: length error mean {sum(err) / n:+.2f} um, rms {rms:.2f} um, "
          f"max |error| {max(abs(e) for e in err):.2f} um, {sum(abs(e) > 5 for e in err)} of {n} above 5 um, {warned} with warnings")
for r in refused:
    print(f"  refused {r}")
PY
}

: > "$work/cases"
case "$mode" in
  lines|wiggles)
    margin=$([ "$mode" = lines ] && echo 1.5 || echo 2.5)  # room for a wiggle of up to 1 mm
    for ((i = 1; i <= cases; i++)); do
      if [ "$mode" = lines ]; then
        # Lengths alternate 100 / 150 mm; the angle is a seeded uniform draw in [-3°, 3°].
        length=$((i % 2 == 0 ? 100 : 150))
        read -r angle extra < <(python3 -c "import random; random.seed($i); print(round(random.uniform(-3, 3), 3), '')")
      else
        length=150
        read -r angle extra < <(python3 -c "
import math, random
random.seed(1000 + $i)
while True:
    a, l = random.uniform(0.05, 1.0), random.uniform(3, 15)
    if math.atan(2 * math.pi * a / l) <= math.radians(46): break
print(round(random.uniform(-3, 3), 3), f'--wiggle-mm {a:.3f} --wiggle-wavelength-mm {l:.2f} --wiggle-decay-mm 30')")
      fi
      # shellcheck disable=SC2086
      "$stiffpath" render-scan "$work/s.png" --length-mm "$length" --angle-deg "$angle" --texture "$texture" --noise "$noise" \
        --margin-mm "$margin" --seed "$i" $extra --json --quiet > "$work/truth_$i.json"
      "$stiffpath" scan "$work/s.png" --json --quiet > "$work/scan_$i.json" 2> "$work/err_$i.txt" || true
      echo "$i" >> "$work/cases"
    done
    summary "$mode$([ "$mode" = lines ] && echo ' (100/150 mm lines, ±3°)' || echo ' (150 mm lines, ±3°)')"
    ;;
  twin)
    for mech in oc-gu sc-gl; do
      for accel in 1g 3g 5g; do
        for comp in "" "--no-compensation"; do
          name="${mech}_${accel}${comp:+_uncompensated}"
          # shellcheck disable=SC2086
          "$stiffpath" run "$root/examples/triangle.gcode" --mechanism "$mech" --accel "$accel" $comp -o "$work/j.csv" > /dev/null
          "$stiffpath" simulate "$work/j.csv" --mechanism "$mech" --sides 3 --marks-csv "$work/marks.csv" > /dev/null
          "$stiffpath" render-scan "$work/s.png" --path-csv "$work/marks.csv" --sides 3 --texture "$texture" --noise "$noise" \
            --json --quiet > "$work/truth_$name.json"
          "$stiffpath" scan "$work/s.png" --shape triangle --json --quiet > "$work/scan_$name.json" 2> "$work/err_$name.txt" || true
          echo "$name" >> "$work/cases"
        done
      done
    done
    summary twin
    ;;
  *) echo "unknown mode '$mode' (lines, wiggles or twin)" >&2; exit 2 ;;
esac
