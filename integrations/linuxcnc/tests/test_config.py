#!/usr/bin/python3
"""`stiffpath linuxcnc config` against the robot file it is given: the robot named once ([STIFFPATH]ROBOT, which
[KINS] reads), the joints' limits and home angles (forward kinematics written out here must give home_mm back), the
axes' limits from the compliance table's rectangle, the model written beside; errors with exit 2 and no output;
and examples/linuxcnc is what the command writes for the thesis robot. Needs no LinuxCNC.
usage: test_config.py STIFFPATH ROBOT_FILE EXAMPLE_DIR WORK_DIR"""
import configparser
import csv
import json
import math
import os
import shutil
import subprocess
import sys

from fivebar import FiveBar
from linuxcnc_checks import Checks

stiffpath, robot_file, example, work = sys.argv[1:5]
check = Checks()


def run(*args):
    return subprocess.run([stiffpath, "linuxcnc", "config"] + list(args), capture_output=True, text=True)


def read_ini(path):
    ini = configparser.ConfigParser(strict=False, interpolation=None, comment_prefixes=("#", ";"))
    ini.optionxform = str
    with open(path) as f:
        ini.read_string(f.read())
    return ini


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
out = os.path.join(work, "asym")
result = run("--robot", robot_file, "-o", out)
check(result.returncode == 0, "config for the robot file: " + result.stderr)
check(sorted(os.listdir(out)) == ["machine.hal", "machine.ini", "model.json", "stream.hal", "tool.tbl"],
      "the folder holds %s" % sorted(os.listdir(out)))
check(not [n for n in os.listdir(work) if n.startswith(".")], "no temporary folder is left beside it")
ini = read_ini(os.path.join(out, "machine.ini"))
robot_path = os.path.realpath(robot_file)
check(ini["STIFFPATH"]["ROBOT"] == robot_path and ini["STIFFPATH"]["MODEL"] == "model.json",
      "[STIFFPATH] names the robot file and the model written beside: %s" % dict(ini["STIFFPATH"]))
check(ini["KINS"]["KINEMATICS"] == "stiffpathkins", "[KINS] names no robot: stiffpathkins reads [STIFFPATH]ROBOT")
texts = {n: open(os.path.join(out, n)).read() for n in ("machine.ini", "machine.hal", "stream.hal")}
settings = [line for t in texts.values() for line in t.splitlines() if not line.lstrip().startswith("#")]
check(sum(line.count(robot_path) for line in settings) == 1, "the robot file is named in one place (comments aside)")
check("loadrt stiffpathcomp\n" in texts["machine.hal"] and "loadrt [KINS]KINEMATICS\n" in texts["machine.hal"],
      "the HAL file loads both modules without naming the robot")
with open(os.path.join(out, "model.json")) as f:
    check(json.load(f)["format"] == "stiffpath-compliance-model", "model.json is a model file")

robot = FiveBar(robot_file)
for i, joint in enumerate(robot.joints):
    section = ini["JOINT_%d" % i]
    check(abs(float(section["MIN_LIMIT"]) - joint["min_deg"]) < 1e-6 and abs(float(section["MAX_LIMIT"]) - joint["max_deg"]) < 1e-6,
          "joint %d: the robot file's position limits" % i)
    check(abs(float(section["MAX_VELOCITY"]) - math.degrees(joint["max_velocity_rad_s"])) < 1e-5 and
          abs(float(section["MAX_ACCELERATION"]) - math.degrees(joint["max_acceleration_rad_s2"])) < 1e-5,
          "joint %d: the robot file's velocity and acceleration limits, in degrees" % i)
    check(section["HOME"] == section["HOME_OFFSET"] and joint["min_deg"] < float(section["HOME"]) < joint["max_deg"],
          "joint %d: homed in place at an angle within its limits" % i)
home = robot.forward_mm(math.radians(float(ini["JOINT_0"]["HOME"])), math.radians(float(ini["JOINT_1"]["HOME"])), robot.home)
check(math.hypot(home[0] - robot.home[0], home[1] - robot.home[1]) < 1e-6,
      "the home angles give home_mm %s back: %s" % (robot.home, home))
with open(os.path.join(os.path.dirname(robot_file), "asym_displacements.csv")) as f:
    points = [(float(r["x_mm"]), float(r["y_mm"])) for r in csv.DictReader(row for row in f if not row.startswith("#"))]
xs, ys = [p[0] for p in points], [p[1] for p in points]
check((float(ini["AXIS_X"]["MIN_LIMIT"]), float(ini["AXIS_X"]["MAX_LIMIT"]), float(ini["AXIS_Y"]["MIN_LIMIT"]),
       float(ini["AXIS_Y"]["MAX_LIMIT"])) == (min(xs), max(xs), min(ys), max(ys)),
      "the axes span the compliance table's rectangle %s" % ((min(xs), max(xs), min(ys), max(ys)),))
check(abs(float(ini["TRAJ"]["MAX_LINEAR_ACCELERATION"]) - 2 * 9806.65) < 0.1, "2 g by default, in mm/s^2")

# Errors: exit 2, the reason, nothing written.
result = run("--robot", robot_file, "-o", out)
check(result.returncode == 2 and "not an empty folder" in result.stderr, "an existing folder is refused: %r" % result.stderr)
check(sorted(os.listdir(out)) == ["machine.hal", "machine.ini", "model.json", "stream.hal", "tool.tbl"], "… and left alone")
for args, says in ((["--workspace-mm", "-60,60,170,330"], "is not all usable"), (["--accel", "-1g"], "--accel"),
                   (["--servo-period-ns", "10"], "--servo-period-ns")):
    target = os.path.join(work, "refused")
    result = run("--robot", robot_file, "-o", target, *args)
    check(result.returncode == 2 and says in result.stderr and not os.path.exists(target),
          "%s: exit 2 naming %s, no folder: %r" % (" ".join(args), says, result.stderr))
check(not [n for n in os.listdir(work) if n.startswith(".")], "no temporary folder is left after the errors")

# The example is this command's output for the thesis robot (the command line is in its INI's header).
header = open(os.path.join(example, "machine.ini")).read().splitlines()[2]
words = header.split()[4:-2]  # "#   stiffpath linuxcnc config ARGS -o <folder>"
result = run(*(words + ["-o", os.path.join(work, "thesis")]))
check(result.returncode == 0, "the example's command: " + result.stderr)
for name in ("machine.ini", "machine.hal", "stream.hal", "tool.tbl"):
    with open(os.path.join(example, name)) as a, open(os.path.join(work, "thesis", name)) as b:
        check(a.read() == b.read(), "examples/linuxcnc/%s is what `%s` writes" % (name, " ".join(header.split()[1:])))

if not check.failures:
    shutil.rmtree(work, ignore_errors=True)
print("FAILED %d checks" % len(check.failures) if check.failures else "PASS")
sys.exit(1 if check.failures else 0)
