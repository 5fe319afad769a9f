#!/usr/bin/env bash
# Peak memory of render-scan and scan on an A4 page at 1200 dpi, as a ratio to the image's bytes.
# Usage: scripts/vision_memory.sh [STIFFPATH_BINARY] [WORK_DIR]
# Prints one line per run: peak resident set (MB, /usr/bin/time -v), the image's 8-bit pixels (MB),
# the ratio, and the wall time. "page" is a 200 × 287 mm polyline on an A4-sized image (210.2 ×
# 297.2 mm, the same command for any version); "plate" is examples/plates/thesis_a4.json (three marks
# and four labels on A4; render-scan --plate, scan --all-marks are needed).
set -euo pipefail
bin=${1:-build/release/bin/stiffpath}
work=${2:-$(mktemp -d)}
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
mkdir -p "$work"
cd "$work"

# peak_mb COMMAND...: runs it, prints "peak_mb wall_s" of the whole process.
measure() {
  /usr/bin/time -v "$@" >/dev/null 2>time.txt || { cat time.txt >&2; return 1; }
  awk -F': ' '/Maximum resident set size/ {kb=$2} /Elapsed \(wall clock\)/ {t=$2}
    END {n=split(t, p, ":"); s=0; for (i=1; i<=n; i++) s=s*60+p[i]; printf "%.1f %.2f\n", kb/1024, s}' time.txt
}

report() {  # name image peak wall
  local px
  px=$(python3 -c "import struct,sys; d=open('$2','rb').read(24); w,h=struct.unpack('>II', d[16:24]); print(w*h)")
  awk -v n="$1" -v p="$3" -v w="$4" -v px="$px" 'BEGIN {printf "%-34s peak %7.1f MB  image %6.1f MB (%.1f Mpx)  ratio %5.2f  wall %6.2f s\n", n, p, px/1048576, px/1e6, p/(px/1048576), w}'
}

read -r base _ < <(measure "$bin" --version)
echo "program alone ($bin --version): peak $base MB"
read -r peak wall < <(measure "$bin" render-scan page.png --shape polyline --vertices-mm "0,0 200,0 200,287" --margin-mm 5 --texture 0.01)
report "render-scan page (A4 polyline)" page.png "$peak" "$wall"
read -r peak wall < <(measure "$bin" scan page.png --shape polyline:2 --json)
report "scan page" page.png "$peak" "$wall"
if "$bin" render-scan --help | grep -q -- --plate; then
  read -r peak wall < <(measure "$bin" render-scan plate.png --plate "$root/examples/plates/thesis_a4.json")
  report "render-scan --plate thesis_a4" plate.png "$peak" "$wall"
  read -r peak wall < <(measure "$bin" scan plate.png --all-marks --json)
  report "scan --all-marks plate" plate.png "$peak" "$wall"
  read -r peak wall < <(measure "$bin" scan plate.png --all-marks --overlay plate_overlay.png --json)
  report "scan --all-marks --overlay plate" plate.png "$peak" "$wall"
fi
