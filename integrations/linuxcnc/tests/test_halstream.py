#!/usr/bin/python3
"""stiffpath-halstream against the joint files it converts (binary read here by its documented layout, and CSV),
its options and its errors. usage: test_halstream.py STIFFPATH HALSTREAM WORK_DIR PROGRAM"""
import math
import os
import shutil
import struct
import subprocess
import sys

stiffpath, halstream, work, program = sys.argv[1:5]
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def run(*args):
    return subprocess.run(list(args), capture_output=True, text=True)


def stream_lines(text):
    return [line.split() for line in text.splitlines() if not line.startswith("#")]


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
job_bin, job_csv = os.path.join(work, "job.bin"), os.path.join(work, "job.csv")
# The program, with a laser-off move in front, so that the laser column has both values.
with open(program) as f:
    text = f.read()
program = os.path.join(work, "job.ngc")
with open(program, "w") as f:
    f.write(text.replace("G61\n", "G61\nG0 X200 Y0\n", 1).replace("S1000", "S600"))
for path, fmt in ((job_bin, "bin"), (job_csv, "csv")):
    result = run(stiffpath, "run", program, "--format", fmt, "-o", path)
    check(result.returncode == 0, "stiffpath run --format %s: %s" % (fmt, result.stderr))

# The binary file by its layout. Version 2: a 128-byte header, 120-byte records of 14 doubles (t, θ, ω, α,
# target, command, force, power), i32 line, u8 laser; version 1: 64 bytes, 112-byte records without power.
with open(job_bin, "rb") as f:
    data = f.read()
_, version, record_bytes, rate_hz, count = struct.unpack_from("<8sIIdQ", data, 0)
header_bytes, layout = {1: (64, "<13diB"), 2: (128, "<14diB")}[version]
records = [struct.unpack_from(layout, data, header_bytes + i * record_bytes) for i in range(count)]
LASER = len(records[0]) - 1
check(rate_hz == 2000.0 and count > 500, "the triangle at 2 kHz has %d samples at %g Hz" % (count, rate_hz))

POWER = 13  # version 2's fourteenth double
check(version == 2, "run writes version 2 (with the power)")

result = run(halstream, job_bin)
check(result.returncode == 0, "converting the binary file: " + result.stderr)
check(result.stdout.startswith("# "), "the stream starts with a comment line for halstreamer")
lines = stream_lines(result.stdout)
check(len(lines) == count + 1 and lines[-1][:3] == lines[-2][:3] and lines[-1][3:] == ["0", "0"],
      "%d lines for %d samples, the last repeated with the laser off" % (len(lines), count))
worst = 0.0
for i, (line, record) in enumerate(zip(lines, records)):
    check(len(line) == 5 and int(line[0]) == i + 1, "line %d: %s" % (i + 1, line))
    for text, theta_rad in zip(line[1:3], record[1:3]):
        worst = max(worst, abs(float(text) - math.degrees(theta_rad)))
check(worst <= 1e-12, "degrees differ from the file's radians by %g" % worst)
check([int(l[3]) for l in lines[:-1]] == [r[LASER] for r in records], "the fourth column is the laser bit")
check([float(l[4]) for l in lines[:-1]] == [r[POWER] if r[LASER] else 0.0 for r in records],
      "the fifth column is the laser power, exactly the file's double")
check(0 < sum(r[LASER] for r in records) < count, "the job switches the laser")
check(any(0.0 < r[POWER] < 1.0 for r in records), "the job has a power between 0 and 1 (S600 of 1000)")

radians = stream_lines(run(halstream, job_bin, "--units", "rad").stdout)
check(all(float(l[1]) == r[1] and float(l[2]) == r[2] for l, r in zip(radians, records)),
      "--units rad gives the file's doubles exactly")
joints = stream_lines(run(halstream, job_bin, "--joints-only").stdout)
check(all(len(l) == 3 and l == full[:3] for l, full in zip(joints, lines)), "--joints-only: the first three columns alone")

# The CSV file carries the same angles to its printed digits.
csv_lines = stream_lines(run(halstream, job_csv).stdout)
with open(job_csv) as f:
    lines_csv = [row.strip() for row in f if not row.startswith("#")]  # the robot's comment line first
    header = lines_csv[0].split(",")
    rows = [row.split(",") for row in lines_csv[1:]]
c1, c2 = header.index("theta1_rad"), header.index("theta2_rad")
check(len(csv_lines) == len(rows) + 1 == count + 1, "the CSV stream has a line per sample")
check(all(abs(float(l[1]) - math.degrees(float(r[c1]))) <= 1e-12 and abs(float(l[2]) - math.degrees(float(r[c2]))) <= 1e-12
          for l, r in zip(csv_lines, rows)), "CSV input: the stream holds the CSV's angles")
cl, cp = header.index("laser"), header.index("power")
check(all(l[3] == r[cl] and float(l[4]) == float(r[cp]) for l, r in zip(csv_lines, rows)),
      "CSV input: the stream holds the CSV's laser and power")

# Errors: exit 2, a message naming the file, and no output file.
out = os.path.join(work, "wrong.stream")
result = run(halstream, job_bin, "--period-ns", "1000000", "-o", out)
check(result.returncode == 2 and job_bin in result.stderr and "--rate 1000" in result.stderr,
      "a 2 kHz file played at 1 kHz is refused with the fix: %r" % result.stderr)
check(not os.path.exists(out), "no output file after an error")
result = run(halstream, os.path.join(work, "missing.bin"))
check(result.returncode == 2 and "missing.bin" in result.stderr, "a missing file: %r" % result.stderr)
result = run(halstream, job_bin, "--units", "furlongs")
check(result.returncode == 2 and "furlongs" in result.stderr, "bad units: %r" % result.stderr)

shutil.rmtree(work, ignore_errors=True)
print("FAILED %d checks" % len(failures) if failures else "PASS")
sys.exit(1 if failures else 0)
