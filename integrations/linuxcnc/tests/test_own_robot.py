#!/usr/bin/python3
"""A machine builder's robot through LinuxCNC, both routes in one command: `stiffpath linuxcnc config` for the robot
file, then `stiffpath linuxcnc run --compare` on a laser job (as root: LinuxCNC runs as a user the command creates or
finds). Checks: LinuxCNC's route against the library through the documented B-spline (check_gcode_record); the streamed
route equal to an independent `stiffpath run` within 1e-9 rad, with the FIFO refilled while it plays; the laser's edges
on both routes against the program's laser-on paths; the comparison's number recomputed here.
usage: test_own_robot.py STIFFPATH CHECK_GCODE_RECORD ROBOT_FILE WORK_DIR"""
import bisect
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

from fivebar import FiveBar
from linuxcnc_checks import Checks, check_laser_edges, read_joint_file, read_record, stretches

stiffpath, checker, robot_file, work = sys.argv[1:5]
check = Checks()
TOLERANCE_RAD = 1e-9
JOB = """(three laser-on paths: M3 at 60 % power, M3 at full power with a corner, M62's synchronised output)
G21 G90 G17 G94
G61
G0 X-40 Y180
M3 S600
G1 X30 Y180 F60000
G1 X30 Y240
M5
G0 X-30 Y240
M3 S1000
G1 X-30 Y200 F30000
G1 X0 Y220
M5
G0 X10 Y230
M62 P0
G1 X20 Y200 F30000
M63 P0
G0 X0 Y210
M2
"""
EXPECTED = [((-40, 180), (30, 240), 0.6), ((-30, 240), (0, 220), 1.0), ((10, 230), (20, 200), 1.0)]

shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
if os.getuid() == 0:
    # LinuxCNC runs as another user, who must reach the work folder and read the robot file: a checkout or build
    # tree under /root is private, so both go to a folder of /tmp (the robot file with its compliance table).
    work = tempfile.mkdtemp(prefix="stiffpath-own-robot-")
    os.chmod(work, 0o755)
    robot_dir = os.path.join(work, "robot")
    os.makedirs(robot_dir)
    for name in os.listdir(os.path.dirname(robot_file)):
        if name.endswith((".json", ".csv")):
            shutil.copy2(os.path.join(os.path.dirname(robot_file), name), robot_dir)
    robot_file = os.path.join(robot_dir, os.path.basename(robot_file))
config, job = os.path.join(work, "config"), os.path.join(work, "laser_edges.ngc")
with open(job, "w") as f:
    f.write(JOB)
result = subprocess.run([stiffpath, "linuxcnc", "config", "--robot", robot_file, "-o", config], capture_output=True, text=True)
if result.returncode != 0:
    sys.exit("FAIL: stiffpath linuxcnc config: " + result.stderr)
ini_path = os.path.join(config, "machine.ini")
with open(ini_path) as f:
    ini = f.read()


def setting(key):
    return re.search(r"^%s = (.*)$" % key, ini, re.M).group(1)


# A FIFO shorter than the job, so that halstreamer refills it while the stream plays.
with open(ini_path, "w") as f:
    f.write(ini.replace("DEPTH = 4000", "DEPTH = 400"))

compare, run_dir = os.path.join(work, "compare"), os.path.join(work, "run")
result = subprocess.run([stiffpath, "linuxcnc", "run", config, job, "--compare", compare, "--work-dir", run_dir],
                        capture_output=True, text=True, timeout=600)
print(result.stdout + result.stderr)
if result.returncode != 0:
    sys.exit("FAIL: stiffpath linuxcnc run exited with %d" % result.returncode)
if os.getuid() == 0:
    check("LinuxCNC refuses" in result.stderr and "runs as user" in result.stderr,
          "as root, the command says which user LinuxCNC runs as")

period_s = int(setting("SERVO_PERIOD")) * 1e-9
model = os.path.join(config, setting("MODEL"))
# 1. LinuxCNC's route: the raw record against the library (B-spline of IK(c), compensation of each c).
result = subprocess.run([checker, os.path.join(run_dir, "machine-record.txt"), setting("ROBOT"), model, "%.9g" % period_s,
                         "1000", "30", "0.005"], capture_output=True, text=True)
print(result.stdout + result.stderr)
check(result.returncode == 0, "LinuxCNC's route: the recorded commands are the library's through the B-spline")

# 2. The streamed route against `stiffpath run` with the configuration's robot, model, limits and servo rate.
reference = os.path.join(work, "reference.bin")
result = subprocess.run([stiffpath, "run", job, "--robot", setting("ROBOT"), "--model", model,
                         "--rate", "%.17g" % (1 / period_s), "--accel", "%.17g" % (float(setting("MAX_LINEAR_ACCELERATION")) / 1000),
                         "--max-velocity-mm-s", setting("MAX_LINEAR_VELOCITY"), "--s-max", setting("S_MAX"),
                         "--format", "bin", "-o", reference], capture_output=True, text=True)
check(result.returncode == 0, "stiffpath run: " + result.stderr)
rate_hz, planned = read_joint_file(reference)
streamed = read_record(os.path.join(compare, "stiffpath.csv"))
check(len(streamed) == len(planned) > 2 * 400, "%d streamed periods for %d samples, more than twice the FIFO"
      % (len(streamed), len(planned)))
worst = 0.0
for row, (t, q1, q2, power, laser, x_m, y_m) in zip(streamed, planned):
    worst = max(worst, abs(row["theta1_rad"] - q1), abs(row["theta2_rad"] - q2))
    if not (abs(row["t_s"] - t) <= 1e-6 and row["laser"] == laser and abs(row["power"] - (power if laser else 0)) <= 1e-9
            and abs(row["x_mm"] - x_m * 1e3) <= 1e-6 and abs(row["y_mm"] - y_m * 1e3) <= 1e-6):
        check(False, "streamed period at t = %s: %s, planned %s" % (row["t_s"], row, (t, laser, power, x_m, y_m)))
        break
print("streamed route: max |recorded - stiffpath run| = %.3g rad over %d periods" % (worst, len(streamed)))
check(worst <= TOLERANCE_RAD, "the streamed joints equal stiffpath run's within %g rad (%.3g)" % (TOLERANCE_RAD, worst))

# 3. The laser's edges on both routes.
machine = read_record(os.path.join(compare, "linuxcnc.csv"))
late = [check_laser_edges(check, machine, EXPECTED, "LinuxCNC's route"), check_laser_edges(check, streamed, EXPECTED, "streamed route")]
print("laser edges: at most %d / %d period(s) from where the paths begin and end" % tuple(late))

# 4. The commanded points are the planned ones moved by a correction (forward kinematics written out here), and the
#    comparison's number recomputed from the two records: the largest distance from a commanded point of one route to
#    the other's commanded path nearby (within 1 mm of planned path length, in the same laser-on stretch).
robot = FiveBar(robot_file)


def commanded(rows):
    return [robot.forward_mm(r["theta1_rad"], r["theta2_rad"], (r["x_mm"], r["y_mm"])) for r in rows]


def laser_path(rows, points):  # per stretch: [(s_mm, command point)]
    out = []
    for on, off in stretches(rows):
        s, path = 0.0, []
        for k in range(on, off):
            if k > on:
                s += math.hypot(rows[k]["x_mm"] - rows[k - 1]["x_mm"], rows[k]["y_mm"] - rows[k - 1]["y_mm"])
            path.append((s, points[k]))
        out.append(path)
    return out


def to_segment(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    length2 = dx * dx + dy * dy
    f = min(1.0, max(0.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2)) if length2 > 0 else 0.0
    return math.hypot(p[0] - (a[0] + f * dx), p[1] - (a[1] + f * dy))


def distance_to_path(path, s, p):  # to the polyline of the points within 1 mm of planned path length, one more each side
    ss = [point[0] for point in path]
    lo = max(0, bisect.bisect_left(ss, s - 1.0) - 1)
    hi = min(len(path), bisect.bisect_right(ss, s + 1.0) + 1)
    best = math.hypot(p[0] - path[lo][1][0], p[1] - path[lo][1][1])
    for i in range(lo, hi - 1):
        best = min(best, to_segment(p, path[i][1], path[i + 1][1]))
    return best


routes = []
for rows in (machine, streamed):
    points = commanded(rows)
    corrections = [math.hypot(p[0] - r["x_mm"], p[1] - r["y_mm"]) * 1e3 for p, r in zip(points, rows) if r["laser"]]
    check(10 < max(corrections) < 200, "the corrections with the laser on are real and plausible: up to %.1f um" % max(corrections))
    routes.append(laser_path(rows, points))
largest = 0.0
for a, b in ((routes[0], routes[1]), (routes[1], routes[0])):
    for stretch_a, stretch_b in zip(a, b):
        for s, p in stretch_a:
            largest = max(largest, distance_to_path(stretch_b, s, p) * 1e3)
with open(os.path.join(compare, "compare.json")) as f:
    summary = json.load(f)
print("compare.json: %s; recomputed %.4f um" % (summary["largest_difference_um"], largest))
check(summary["comparable"] and summary["laser_stretches"] == 3, "the comparison pairs the three laser-on paths")
check(abs(summary["largest_difference_um"] - largest) <= 1e-3, "the routes' largest difference, recomputed: %.4f um" % largest)
if shutil.which("gnuplot"):
    check(os.path.getsize(os.path.join(compare, "compare.svg")) > 1000, "the comparison's figure")

if not check.failures:
    shutil.rmtree(work, ignore_errors=True)
print("FAILED %d checks" % len(check.failures) if check.failures else "PASS")
sys.exit(1 if check.failures else 0)
