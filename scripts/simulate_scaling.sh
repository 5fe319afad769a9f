#!/usr/bin/env bash
# Time (wall and CPU, medians) and peak memory of `stiffpath simulate` against the job's length: jobs of repeated small
# triangles and lines (one laser stroke each, travel moves between) of about 10, 50, 200, 500 and
# 3600 s of motion, planned at 3 g, simulated from their binary joint files.
# Usage: scripts/simulate_scaling.sh [BUILD_DIR] [SECONDS ...]   (default build/release, all lengths)
set -euo pipefail
build=${1:-build/release}
shift || true
lengths=("$@")
[ ${#lengths[@]} -gt 0 ] || lengths=(10 50 200 500 3600)
bin="$build/bin/stiffpath"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# One pattern (a 30 mm triangle, then a 40 mm line) lasts about 0.4 s at 3 g.
make_job() {
  /usr/bin/python3 - "$1" <<'PY'
import sys
repeats = max(1, round(float(sys.argv[1]) / 0.4))
print("G21 G90 G17 G94\nG61")
for i in range(repeats):
    x = 185 + (i % 5) * 10
    y = -60 + (i % 7) * 15
    print(f"G0 X{x:.3f} Y{y:.3f}\nM3 S1000")
    print(f"G1 X{x + 30:.3f} Y{y:.3f} F120000\nG1 X{x + 15:.3f} Y{y + 25.98:.3f}\nG1 X{x:.3f} Y{y:.3f}\nM5")
    print(f"G0 X{x:.3f} Y{y + 8:.3f}\nM3 S1000\nG1 X{x + 40:.3f} Y{y + 8:.3f}\nM5")
print("M2")
PY
}
for s in "${lengths[@]}"; do
  make_job "$s" > "$work/job_$s.gcode"
  "$bin" run "$work/job_$s.gcode" --accel 3g --format bin -o "$work/job_$s.bin" > /dev/null
  duration=$("$bin" simulate "$work/job_$s.bin" --json | /usr/bin/python3 -c 'import json,sys; print(json.load(sys.stdin)["duration_s"])')
  for run in $(seq "${RUNS:-3}"); do
    /usr/bin/time -f "%e %U %S %M" -a -o "$work/t_$s" "$bin" simulate "$work/job_$s.bin" > /dev/null
  done
  # Medians of wall and CPU (user + system) time over the runs, the largest peak RSS.
  /usr/bin/python3 - "$s" "$duration" "$work/t_$s" <<'PY'
import statistics, sys
rows = [list(map(float, line.split())) for line in open(sys.argv[3]) if line.strip()]
wall = statistics.median(r[0] for r in rows)
cpu = statistics.median(r[1] + r[2] for r in rows)
rss = max(r[3] for r in rows) / 1024
duration = float(sys.argv[2])
print(f"{sys.argv[1]:>5} s job ({duration:8.1f} s of motion): CPU {cpu:7.2f} s ({1e3 * cpu / duration:5.2f} ms per "
      f"simulated s), wall {wall:7.2f} s, peak RSS {rss:6.1f} MiB ({len(rows)} runs)")
PY
done
