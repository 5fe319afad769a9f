#!/usr/bin/env bash
# Test (2): a job planned and compensated by `stiffpath run`, converted by stiffpath-halstream, streamed into the
# servo thread of the example's stream.hal under halrun and recorded by halsampler; equal to the file within 1e-9 rad.
# usage: run_stream_test.sh SOURCE_DIR WORK_DIR STIFFPATH HALSTREAM PROGRAM
set -euo pipefail
source_dir=$1 work=$2 stiffpath=$3 halstream=$4 program=$5
here=$(cd "$(dirname "$0")" && pwd)
source "$here/linuxcnc_env.sh"

prepare_work_dir "$work"
cp "$source_dir/examples/linuxcnc/stream.hal" "$here/record-stream.hal" "$work/"
period_ns=$(sed -n 's/^SERVO_PERIOD *= *//p' "$source_dir/examples/linuxcnc/stream.ini")
rate_hz=$(awk -v p="$period_ns" 'BEGIN { printf "%.9g", 1e9 / p }')
"$stiffpath" run "$program" --rate "$rate_hz" --format bin -o "$work/job.bin" > "$work/run.txt"
"$halstream" "$work/job.bin" --period-ns "$period_ns" -o "$work/job.stream"
samples=$(grep -vc '^#' "$work/job.stream")
# Depth below the job's length, so that halstreamer refills the FIFO while it plays; two seconds of margin after.
depth=$(( samples / 2 > 100 ? samples / 2 : 100 ))
cat > "$work/stream-test.ini" <<INI
[STREAM]
SERVO_PERIOD = $period_ns
DEPTH = $depth
FILE = $work/job.stream
RECORD = $work/record.txt
RECORD_SAMPLES = $(( samples + 2 * ${rate_hz%.*} ))
INI
hand_over_work_dir "$work"
cd "$work"
if ! timeout 300 halrun -i stream-test.ini -f record-stream.hal > halrun.log 2>&1; then
  echo "halrun failed; the end of its log:"; grep -v 'fallback_uid' halrun.log | tail -20
  exit 1
fi
/usr/bin/python3 "$here/check_stream_record.py" job.bin record.txt
