#!/usr/bin/env bash
# The main job on the built-in default (the thesis's OC robot with G_U and its data), as the README's demo shows it.
set -euo pipefail
stiffpath=${1:-build/dev/bin/stiffpath}

echo "== stiffpath $("$stiffpath" --version | cut -d' ' -f2): the thesis's robot (oc-gu)"
"$stiffpath" mechanism show oc-gu
echo
echo "== inverse kinematics on the thesis's 3 x 5 measurement grid (eq. 2.2), checked by forward kinematics (eq. 2.1)"
"$stiffpath" kin grid
echo
echo "== mobility (eqs. 3.1-3.2)"
"$stiffpath" mobility
echo
echo "== the thesis's y motion (fig. 4.7a) planned at 5 g, jerk-limited, sampled at 2 kHz (thesis 4.3)"
"$stiffpath" plan examples/y_motion.gcode
