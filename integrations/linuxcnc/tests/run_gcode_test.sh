#!/usr/bin/env bash
# Test (1): a G-code job through LinuxCNC (headless, `linuxcnc -r`) with stiffpathkins and stiffpathcomp on the
# example machine, recorded by halsampler and checked against the library by check_gcode_record.
# usage: run_gcode_test.sh SOURCE_DIR WORK_DIR MODULE_DIR CHECKER PROGRAM
# Exit 77 (skipped) when the modules in LinuxCNC's module directory are not the ones just built.
set -euo pipefail
source_dir=$1 work=$2 module_dir=$3 checker=$4 program=$5
here=$(cd "$(dirname "$0")" && pwd)
source "$here/linuxcnc_env.sh"
require_installed_modules "$module_dir"

example="$source_dir/examples/linuxcnc"
prepare_work_dir "$work"
cp "$example/stiffpath-fivebar.hal" "$example/tool.tbl" "$here/record.hal" "$here/test-ui.py" "$work/"
cp "$program" "$work/job.ngc"
# The example's machine, with this test as its display and the recorder as a second HAL file.
sed -e 's|^DISPLAY = axis|DISPLAY = ./test-ui.py|' -e '/^OPEN_FILE/d' \
    -e 's|^HALFILE = stiffpath-fivebar.hal|HALFILE = stiffpath-fivebar.hal\nHALFILE = record.hal|' \
    "$example/stiffpath-fivebar.ini" > "$work/test.ini"
hand_over_work_dir "$work"

cd "$work"
export STIFFPATH_TEST_PROGRAM="$work/job.ngc" STIFFPATH_TEST_RECORD="$work/record.txt" STIFFPATH_TEST_RESULT="$work/result.txt"
if ! timeout 300 linuxcnc -r test.ini > linuxcnc.log 2>&1; then
  echo "linuxcnc -r failed; the end of its log:"; grep -v 'fallback_uid' linuxcnc.log | tail -20
  [ -f result.txt ] && cat result.txt
  exit 1
fi
grep -qx ok result.txt || { echo "test-ui.py: $(cat result.txt)"; exit 1; }
robot=$(sed -n 's/^ROBOT *= *//p' test.ini)
model=$(sed -n 's/^MODEL *= *//p' test.ini)
period_ns=$(sed -n 's/^SERVO_PERIOD *= *//p' test.ini)
"$checker" record.txt "$robot" "$model" "$(awk -v p="$period_ns" 'BEGIN { printf "%.9g", p * 1e-9 }')" 1000
