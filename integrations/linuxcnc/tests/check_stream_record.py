#!/usr/bin/python3
"""Test (2): the joint commands recorded from the servo thread equal the joint file's within 1e-9 rad.

usage: check_stream_record.py JOINT_FILE RECORD
JOINT_FILE is the binary file of `stiffpath run --format bin`, read here with its documented layout
(docs/compensation.md), independently of the converter; RECORD is halsampler's output of record-stream.hal:
period number, stream sample number, theta1 and theta2 in millidegrees."""
import math
import struct
import sys

TOLERANCE_RAD = 1e-9


def read_joint_file(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, version, record_bytes, rate_hz, count = struct.unpack_from("<8sIIdQ", data, 0)
    layouts = {1: (64, 112), 2: (128, 120)}  # version: (header bytes, record bytes)
    if magic != b"SPJOINT\0" or layouts.get(version, (0, 0))[1] != record_bytes:
        sys.exit("FAIL: %s is not a version-1 or version-2 stiffpath binary joint file" % path)
    header = layouts[version][0]
    if len(data) != header + count * record_bytes:
        sys.exit("FAIL: %s: %d bytes for %d records" % (path, len(data), count))
    return [struct.unpack_from("<3d", data, header + i * record_bytes)[1:] for i in range(count)]


def main():
    joints = read_joint_file(sys.argv[1])
    rows = []
    with open(sys.argv[2]) as f:
        for number, line in enumerate(f, 1):
            if "overrun" in line:
                sys.exit("FAIL: %s:%d: halsampler overrun" % (sys.argv[2], number))
            period, sample, j0, j1 = line.split()
            rows.append((int(period), int(sample), float(j0), float(j1)))
    if any(b[0] != a[0] + 1 for a, b in zip(rows, rows[1:])):
        sys.exit("FAIL: the record skips servo periods")
    streamed = [r for r in rows if r[1] > 0]
    if not streamed:
        sys.exit("FAIL: nothing was streamed")
    # Sample numbers 1..N, one per period: after the last, streamer holds it (the FIFO is empty).
    numbers = [r[1] for r in streamed]
    last = numbers.index(len(joints)) if len(joints) in numbers else None
    if last is None or numbers[: last + 1] != list(range(1, len(joints) + 1)) or any(n != len(joints) for n in numbers[last:]):
        sys.exit("FAIL: the stream's sample numbers are not 1..%d once each (an underrun or a lost line)" % len(joints))
    worst = 0.0
    for (_, sample, j0_mdeg, j1_mdeg) in streamed[: last + 1]:
        theta = joints[sample - 1]
        for recorded_mdeg, expected_rad in zip((j0_mdeg, j1_mdeg), theta):
            worst = max(worst, abs(math.radians(recorded_mdeg * 1e-3) - expected_rad))
    print("samples %d  periods recorded %d  max |recorded - file| %.3g rad" % (len(joints), len(rows), worst))
    if not worst <= TOLERANCE_RAD:
        sys.exit("FAIL: recorded joint commands differ from the file's by more than %g rad" % TOLERANCE_RAD)
    print("PASS")


main()
