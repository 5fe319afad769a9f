#!/usr/bin/env python3
"""Compares two joint files written by `stiffpath run` (both binary or both CSV) field by field.

Usage: compare_joints.py REFERENCE CANDIDATE [--angle-tol 1e-12]
Binary files: exits 0 when the files have the same samples, identical times, lines and laser
states, joint angles within --angle-tol rad and every other field within --relative-tol of its
largest magnitude (round-off). CSV files: every cell within one unit of its last printed digit.
Prints the largest difference of each field either way. Standard library only.
"""
import argparse
import csv
import struct
import sys

BIN_FIELDS = ["t_s", "theta1_rad", "theta2_rad", "omega1_rad_s", "omega2_rad_s", "alpha1_rad_s2", "alpha2_rad_s2",
              "x_m", "y_m", "xcmd_m", "ycmd_m", "fx_n", "fy_n", "line", "laser"]
# Binary versions: (header bytes, record layout, fields); version 2 adds the power after Fy.
LAYOUTS = {1: (64, struct.Struct("<13dib3x"), BIN_FIELDS),
           2: (128, struct.Struct("<14dib3x"), BIN_FIELDS[:13] + ["power"] + BIN_FIELDS[13:])}
ANGLES = {"theta1_rad", "theta2_rad"}
EXACT = {"t_s", "line", "laser"}
# CSV cells are fixed-point: a round-off difference may flip the last printed digit.
CSV_LAST_DIGIT = {"t_s": 1e-6, "theta1_rad": 1e-9, "theta2_rad": 1e-9, "omega1_rad_s": 1e-9, "omega2_rad_s": 1e-9,
                  "alpha1_rad_s2": 1e-6, "alpha2_rad_s2": 1e-6, "power": 1e-6,
                  "x_mm": 1e-6, "y_mm": 1e-6, "xcmd_mm": 1e-6, "ycmd_mm": 1e-6, "fx_n": 1e-4, "fy_n": 1e-4}


def read_binary(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"SPJOINT\0":
        raise SystemExit(f"{path}: not a binary joint file")
    version = struct.unpack_from("<I", data, 8)[0]
    if version not in LAYOUTS:
        raise SystemExit(f"{path}: binary joint file version {version}, not one of {sorted(LAYOUTS)}")
    header, record, fields = LAYOUTS[version]
    count = struct.unpack_from("<Q", data, 24)[0]
    rows = [record.unpack_from(data, header + k * record.size) for k in range(count)]
    return fields, rows, data[:header]


def read_csv(path):
    with open(path, newline="") as f:
        reader = csv.reader(row for row in f if not row.startswith("#"))
        header = next(reader)
        rows = [tuple(float(v) for v in row) for row in reader]
    return header, rows, ",".join(header).encode()


def read(path):
    with open(path, "rb") as f:
        binary = f.read(8) == b"SPJOINT\0"
    return read_binary(path) if binary else read_csv(path)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("reference")
    parser.add_argument("candidate")
    parser.add_argument("--angle-tol", type=float, default=1e-12)
    parser.add_argument("--relative-tol", type=float, default=1e-9)
    args = parser.parse_args()
    fields, ref, ref_head = read(args.reference)
    cand_fields, cand, cand_head = read(args.candidate)
    if fields != cand_fields or ref_head != cand_head:
        print("headers differ")
        return 1
    if len(ref) != len(cand):
        print(f"sample counts differ: {len(ref)} vs {len(cand)}")
        return 1
    ok = True
    for i, name in enumerate(fields):
        scale = max((abs(r[i]) for r in ref), default=0.0)
        worst = max((abs(r[i] - c[i]) for r, c in zip(ref, cand)), default=0.0)
        if name in CSV_LAST_DIGIT and fields != BIN_FIELDS:
            bad = worst > CSV_LAST_DIGIT[name] * 1.000001
        elif name in EXACT or name == "line" or name == "laser":
            bad = worst != 0.0
        elif name in ANGLES:
            bad = worst > args.angle_tol
        else:
            bad = worst > args.relative_tol * max(scale, 1e-300)
        ok = ok and not bad
        print(f"  {name:14s} max |diff| {worst:.3e}  (max |value| {scale:.3e}){'  FAIL' if bad else ''}")
    print(f"  {len(ref)} samples: {'equivalent' if ok else 'DIFFERENT'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
