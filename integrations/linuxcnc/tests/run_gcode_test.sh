#!/usr/bin/env bash
# A G-code job through LinuxCNC on the example machine (examples/linuxcnc) with `stiffpath linuxcnc run`, its raw
# record checked against the library by check_gcode_record.
# usage: run_gcode_test.sh STIFFPATH WORK_DIR MODULE_DIR CHECKER EXAMPLE_DIR PROGRAM (WORK_DIR: removed; the work goes to /tmp)
# Exit 77 (skipped) when the modules in LinuxCNC's module directory are not the ones just built.
set -euo pipefail
stiffpath=$1 work=$2 module_dir=$3 checker=$4 example=$5 program=$6
here=$(cd "$(dirname "$0")" && pwd)
source "$here/linuxcnc_env.sh"
require_installed_modules "$module_dir"

rm -rf "$work"
# As root LinuxCNC runs as another user, who must reach the work folder: one in /tmp (a build tree may be private).
run_dir=$(mktemp -d /tmp/stiffpath-gcode-test.XXXXXX)
trap 'rm -rf "$run_dir"' EXIT
"$stiffpath" linuxcnc run "$example" "$program" --work-dir "$run_dir"
setting() { sed -n "s/^$1 *= *//p" "$example/machine.ini"; }
period_s=$(awk -v p="$(setting SERVO_PERIOD)" 'BEGIN { printf "%.9g", p * 1e-9 }')
"$checker" "$run_dir/machine-record.txt" "$(setting ROBOT)" "$(setting MODEL)" "$period_s" 1000
