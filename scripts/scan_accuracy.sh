#!/usr/bin/env bash
# Accuracy sweep of `stiffpath scan` on rendered lines: length error against the truth over seeded random cases.
# Usage: scripts/scan_accuracy.sh [stiffpath] [cases] [texture] [noise]   (defaults: build/dev/bin/stiffpath 40 0.01 0.01)
set -euo pipefail
stiffpath=$(realpath "${1:-build/dev/bin/stiffpath}")
cases=${2:-40}
texture=${3:-0.01}
noise=${4:-0.01}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for ((i = 1; i <= cases; i++)); do
  # Lengths alternate 100 / 150 mm; the angle is a seeded uniform draw in [-3°, 3°].
  length=$((i % 2 == 0 ? 100 : 150))
  angle=$(python3 -c "import random; random.seed($i); print(round(random.uniform(-3, 3), 3))")
  "$stiffpath" render-scan "$work/s.png" --length-mm "$length" --angle-deg "$angle" --texture "$texture" --noise "$noise" \
    --margin-mm 1.5 --seed "$i" --json > "$work/truth_$i.json"
  "$stiffpath" scan "$work/s.png" --json > "$work/scan_$i.json"
done

python3 - "$work" "$cases" "$texture" "$noise" <<'PY'
import json, math, sys
work, n, texture, noise = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
err = []
for i in range(1, n + 1):
    t = json.load(open(f"{work}/truth_{i}.json"))
    s = json.load(open(f"{work}/scan_{i}.json"))
    err.append((s["length_mm"] - t["length_mm"]) * 1000)
rms = math.sqrt(sum(e * e for e in err) / n)
print(f"{n} lines (100/150 mm, ±3°), texture {texture}, noise {noise}: length error "
      f"mean {sum(err) / n:+.2f} µm, rms {rms:.2f} µm, max |error| {max(abs(e) for e in err):.2f} µm, "
      f"{sum(abs(e) > 5 for e in err)} of {n} above 5 µm")
PY
