#!/usr/bin/env python3
"""Mutation campaign through the command line: each reader's valid files, mutated, fed to the command that reads them.

Every run must end in exit 0 (the input was still valid) or exit 2 (refused with a message); exit 1 (internal error)
and death by a signal are findings, copied with their command to FINDINGS_DIR. Runs are bounded by a timeout and an
address-space limit, so a runaway read shows up as a finding rather than as a stuck machine. Not part of CI: the full
campaign (10 000 runs per reader) takes hours on a shared machine.

usage: cli_mutation.py STIFFPATH_BIN [--runs N] [--readers robot,model,...] [--seed S] [--findings DIR]
                       [--timeout SECONDS] [--memory-mb MB]
"""
import argparse
import collections
import os
import random
import resource
import shutil
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)

# Numbers a hostile file might hold in place of a valid one.
EXTREMES = ["nan", "NaN", "inf", "-inf", "1e308", "-1e308", "1e400", "5e-324", "-0", "0", "1e12", "1e13", "-1",
            "999999999999999999999", "0x10", "1e", "", "fast", "\"\"", "null", "[]", "{}", "true"]


def read(path):
    with open(path, "rb") as f:
        return f.read()


def mutate(data: bytes, rnd: random.Random) -> bytes:
    """One to three mutations of the kinds a fuzzer and a careless editor make."""
    out = bytearray(data)
    for _ in range(rnd.randint(1, 3)):
        kind = rnd.randrange(11)
        n = len(out)
        at = rnd.randrange(n + 1) if n else 0
        if kind == 0 and n:  # bit flip
            i = rnd.randrange(n)
            out[i] ^= 1 << rnd.randrange(8)
        elif kind == 1 and n:  # delete a run
            del out[at:at + rnd.randint(1, 16)]
        elif kind == 2:  # insert random bytes
            out[at:at] = bytes(rnd.randrange(256) for _ in range(rnd.randint(1, 8)))
        elif kind == 3:  # a number replaced by an extreme value
            digits = [i for i, c in enumerate(out) if chr(c).isdigit()]
            if digits:
                i = rnd.choice(digits)
                j = i
                while j < len(out) and (chr(out[j]).isdigit() or chr(out[j]) in ".eE+-"):
                    j += 1
                while i > 0 and (chr(out[i - 1]).isdigit() or chr(out[i - 1]) in ".-"):
                    i -= 1
                out[i:j] = rnd.choice(EXTREMES).encode()
        elif kind == 4:  # a line duplicated
            lines = bytes(out).split(b"\n")
            k = rnd.randrange(len(lines))
            lines.insert(k, lines[k])
            out = bytearray(b"\n".join(lines))
        elif kind == 5:  # a line deleted
            lines = bytes(out).split(b"\n")
            if len(lines) > 1:
                del lines[rnd.randrange(len(lines))]
            out = bytearray(b"\n".join(lines))
        elif kind == 6 and n:  # truncated
            del out[rnd.randrange(n):]
        elif kind == 7:  # deep nesting or a long run of one byte
            c = rnd.choice([b"[", b"{\"a\":", b"\"", b",", b"9", b"\xff", b"G1"])
            out[at:at] = c * rnd.choice([100, 1000, 30000])
        elif kind == 8:  # invalid UTF-8 in a name
            out[at:at] = rnd.choice([b"\xff\xfe", b"\xc3", b"\xed\xa0\x80", b"\xf4\x90\x80\x80"])
        elif kind == 9 and n:  # a chunk repeated
            i = rnd.randrange(n)
            chunk = bytes(out[i:i + rnd.randint(1, 200)])
            out[at:at] = chunk * rnd.randint(2, 50)
        elif kind == 10:  # a separator swapped
            seps = [i for i, c in enumerate(out) if chr(c) in ",:;[]{}\n"]
            if seps:
                out[rnd.choice(seps)] = ord(rnd.choice(",:;[]{}\n\t "))
    return bytes(out)


def readers(bin_path, work):
    """reader -> (seed files, command builder taking the mutated file's path)."""
    robots = [os.path.join(root, "data", "robots", f) for f in sorted(os.listdir(os.path.join(root, "data", "robots")))]
    robot_seeds = []
    for r in robots + [os.path.join(root, "examples", "robots", "asym_5bar.json")]:
        text = read(r).replace(b'"../thesis/', b'"builtin:thesis/')
        p = os.path.join(work, "seed_" + os.path.basename(r))
        with open(p, "wb") as f:
            f.write(text)
        robot_seeds.append(p)
    model = os.path.join(work, "model.json")
    subprocess.run([bin_path, "fit", "--robot", "oc-gu", "--method", "bilinear", "-o", model], check=True,
                   stdout=subprocess.DEVNULL)
    model_phys = os.path.join(work, "model_physical.json")
    subprocess.run([bin_path, "fit", "--robot", "oc-gu", "--method", "physical", "-o", model_phys], check=True,
                   stdout=subprocess.DEVNULL)
    job = os.path.join(work, "job.gcode")
    with open(job, "w") as f:
        f.write("G21 G90\nG0 X200 Y0\nM3 S500\nG1 X210 F6000\nG1 Y10\nM5\n")
    joints_csv, joints_bin = os.path.join(work, "j.csv"), os.path.join(work, "j.bin")
    subprocess.run([bin_path, "run", job, "-o", joints_csv], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([bin_path, "run", job, "-o", joints_bin, "--format", "bin"], check=True, stdout=subprocess.DEVNULL)
    table = os.path.join(work, "table.csv")
    subprocess.run([bin_path, "campaign", "simulate", "--robot", "oc-gu", "-o", os.path.join(work, "c.csv"),
                    "--truth-output", table], check=True, stdout=subprocess.DEVNULL)
    campaign = os.path.join(work, "c.csv")
    trials = os.path.join(root, "data", "thesis", "repeatability.csv")
    plate = os.path.join(root, "examples", "plates", "thesis_a4.json")
    gcodes = [os.path.join(root, "examples", g) for g in ("triangle.gcode", "x_motion.gcode", "nameplate.gcode")]
    # A calibration plate (every kind of mark) and what calibrate fit reads beside it: the plate's joint file and a
    # small scan with its resolution, on which no fiducial is found (a valid plate ends in exit 2 at the scan).
    plate_dir = os.path.join(work, "cal")
    subprocess.run([bin_path, "calibrate", "plate", "--robot", "oc-gu", "-o", plate_dir], check=True,
                   stdout=subprocess.DEVNULL)
    cal_plate = os.path.join(plate_dir, "plate.json")
    cal_joints = os.path.join(plate_dir, "plate_joints.bin")
    subprocess.run([bin_path, "run", os.path.join(plate_dir, "plate.gcode"), "-o", cal_joints, "--format", "bin"],
                   check=True, stdout=subprocess.DEVNULL)
    cal_scan = os.path.join(plate_dir, "scan.png")
    subprocess.run([bin_path, "render-scan", cal_scan, "--length-mm", "5", "--dpi", "300", "--quiet"], check=True,
                   stdout=subprocess.DEVNULL)
    return {
        "robot": (robot_seeds, lambda p: [bin_path, "robot", "show", p]),
        "robot_run": (robot_seeds, lambda p: [bin_path, "run", job, "--robot", p, "-o", "/dev/null"]),
        "model": ([model, model_phys], lambda p: [bin_path, "run", job, "--model", p, "-o", "/dev/null"]),
        "table": ([table], lambda p: [bin_path, "data", "check", p]),
        "table_fit": ([table], lambda p: [bin_path, "fit", p, "--method", "bilinear"]),
        "campaign": ([campaign], lambda p: [bin_path, "measure", p, "-o", os.path.join(work, "out_table.csv")]),
        "repeatability": ([trials] if os.path.exists(trials) else [], lambda p: [bin_path, "repeatability", p]),
        "joints_csv": ([joints_csv], lambda p: [bin_path, "simulate", p, "--quiet"]),
        "joints_bin": ([joints_bin], lambda p: [bin_path, "simulate", p, "--quiet"]),
        "gcode": (gcodes, lambda p: [bin_path, "plan", p]),
        "plate": ([plate], lambda p: [bin_path, "render-scan", os.path.join(work, "plate.png"), "--plate", p,
                                      "--dpi", "50"]),
        "calibration_plate": ([cal_plate], lambda p: [bin_path, "calibrate", "fit", p, cal_scan, "--joints", cal_joints,
                                                      "--robot", "oc-gu", "-o", os.path.join(work, "cal_out.json")]),
    }


def limit(memory_mb):
    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (memory_mb << 20, memory_mb << 20))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bin")
    ap.add_argument("--runs", type=int, default=10000)
    ap.add_argument("--readers", default="")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--findings", default="build/mutation_findings")
    ap.add_argument("--timeout", type=float, default=60.0)
    ap.add_argument("--memory-mb", type=int, default=4096)
    a = ap.parse_args()
    bin_path = os.path.abspath(a.bin)
    work = tempfile.mkdtemp(prefix="stiffpath-mutation-")
    try:
        table = readers(bin_path, work)
        chosen = a.readers.split(",") if a.readers else list(table)
        os.makedirs(a.findings, exist_ok=True)
        for name in chosen:
            seeds, command = table[name]
            if not seeds:
                print(f"{name}: no seed file, skipped")
                continue
            seed_data = [read(s) for s in seeds]
            rnd = random.Random(f"{a.seed}-{name}")
            codes = collections.Counter()
            findings = timeouts = 0
            slowest = 0.0
            start = time.time()
            suffix = os.path.splitext(seeds[0])[1]
            path = os.path.join(work, f"mutant_{name}{suffix}")
            for run in range(a.runs):
                data = mutate(rnd.choice(seed_data), rnd)
                with open(path, "wb") as f:
                    f.write(data)
                cmd = command(path)
                t0 = time.time()
                try:
                    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=a.timeout,
                                       preexec_fn=limit(a.memory_mb), cwd=work)
                    code = r.returncode
                except subprocess.TimeoutExpired:
                    code, r = "timeout", None
                    timeouts += 1
                slowest = max(slowest, time.time() - t0)
                codes[code] += 1
                if code not in (0, 2):
                    findings += 1
                    keep = os.path.join(a.findings, f"{name}-{run}{suffix}")
                    shutil.copyfile(path, keep)
                    with open(keep + ".txt", "w") as f:
                        f.write(" ".join(cmd).replace(path, keep) + f"\nexit {code}\n")
                        if r is not None:
                            f.write(r.stderr.decode("utf-8", "replace")[-4000:])
            seen = ", ".join(f"{k}: {v}" for k, v in sorted(codes.items(), key=lambda kv: str(kv[0])))
            crashes = sum(v for k, v in codes.items() if isinstance(k, int) and k < 0)
            print(f"{name}: {a.runs} runs in {time.time() - start:.0f} s (slowest {slowest:.1f} s); exit codes {seen}; "
                  f"crashes {crashes}, exit 1: {codes.get(1, 0)}, timeouts {timeouts}, findings {findings}", flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)


main()
