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
echo "-- without compensation (the planned path as it is)"
"$stiffpath" run examples/triangle.gcode --accel 5g --no-compensation -o "$out/triangle_plain.csv"
echo "-- with compliance compensation (run's default: the damped tip's deflection inverted, dynamic, on a reference"
echo "   smoothed over 8 ms; the summary names the model and every filter)"
"$stiffpath" run examples/triangle.gcode --accel 5g -o "$out/triangle_compensated.csv"
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
