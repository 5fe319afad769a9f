#!/usr/bin/env bash
# The main job on the built-in default (the thesis's OC robot with G_U and its data), as the README's demo shows it.
set -euo pipefail
stiffpath=${1:-build/dev/bin/stiffpath}
out=${DEMO_OUTPUT_DIR:-build/demo}
mkdir -p "$out"

echo "== stiffpath $("$stiffpath" --version | cut -d' ' -f2): the thesis's robot (oc-gu) and its measured compliance"
"$stiffpath" robot show oc-gu
echo
echo "== the main job (fig. 4.3): the thesis's triangle at 5 g, G-code -> joint commands at 2 kHz"
echo "-- without compensation"
"$stiffpath" run examples/triangle.gcode --accel 5g --no-compensation -o "$out/triangle_plain.csv"
echo "-- with compliance compensation (F = -m a, delta = C(p) F, p_cmd = p - delta)"
"$stiffpath" run examples/triangle.gcode --accel 5g -o "$out/triangle_compensated.csv"
echo
echo "== how much the commands differ: the largest joint-angle change the compensation makes"
awk -F, 'NR == FNR { if (FNR > 1) { a[FNR] = $2; b[FNR] = $3 } next }
         FNR > 1 { d1 = $2 - a[FNR]; d2 = $3 - b[FNR]; if (d1 < 0) d1 = -d1; if (d2 < 0) d2 = -d2;
                   if (d1 > m1) { m1 = d1; t1 = $1 } if (d2 > m2) { m2 = d2; t2 = $1 } }
         END { printf "theta1: %.1f urad (at t = %s s), theta2: %.1f urad (at t = %s s)\n", m1 * 1e6, t1, m2 * 1e6, t2 }' \
    "$out/triangle_plain.csv" "$out/triangle_compensated.csv"
echo
echo "== what the robot would mark: both command sets on the digital twin (compliant tip, 20 kHz)"
echo "-- without compensation"
"$stiffpath" simulate "$out/triangle_plain.csv" --sides 3
echo "-- with compensation"
"$stiffpath" simulate "$out/triangle_compensated.csv" --sides 3
echo
echo "== which compliance model to trust: leave-one-out cross-validation on the thesis's OC data"
"$stiffpath" cv --robot oc-gu
echo
echo "joint trajectories: $out/triangle_plain.csv, $out/triangle_compensated.csv"
