#!/usr/bin/python3
"""`stiffpath linuxcnc run` started by an unprivileged user (as root, this test starts it as `nobody` with runuser, from
copies in /tmp of the program, the robot file and the job, which `nobody` may not reach where they are): the
job runs headless in LinuxCNC without any help from root, and the record has the documented columns, one row per
servo period, the square's laser edges where its path begins and ends, and commands that are the planned points
moved by a plausible correction (forward kinematics written out here).
usage: test_as_user.py STIFFPATH ROBOT_FILE JOB WORK_DIR"""
import math
import os
import pwd
import re
import shutil
import subprocess
import sys
import tempfile

from fivebar import FiveBar
from linuxcnc_checks import Checks, check_laser_edges, read_record

stiffpath, robot_file, job, work = sys.argv[1:5]
check = Checks()
USER = "nobody"

shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
env = dict(os.environ)
if os.getuid() == 0:
    # The user may not reach the build tree (a checkout under /root): what it needs is copied into a folder of /tmp
    # in the layout of an install (bin, libexec/stiffpath, the library found through LD_LIBRARY_PATH).
    user = pwd.getpwnam(USER)
    work = tempfile.mkdtemp(prefix="stiffpath-as-user-")
    os.chmod(work, 0o755)
    tools = os.path.join(work, "tools")
    for folder in ("bin", "lib", os.path.join("libexec", "stiffpath")):
        os.makedirs(os.path.join(tools, folder))
    build = os.path.dirname(os.path.dirname(os.path.realpath(stiffpath)))
    shutil.copy2(stiffpath, os.path.join(tools, "bin"))
    shutil.copy2(os.path.join(build, "libexec", "stiffpath", "stiffpath-linuxcnc-ui"), os.path.join(tools, "libexec", "stiffpath"))
    ldd = subprocess.run(["ldd", stiffpath], capture_output=True, text=True).stdout
    for library in re.findall(r"=> (\S+) ", ldd):
        if os.path.realpath(library).startswith(build + os.sep):
            shutil.copy2(library, os.path.join(tools, "lib"))
    env["LD_LIBRARY_PATH"] = os.path.join(tools, "lib")
    stiffpath = os.path.join(tools, "bin", os.path.basename(stiffpath))
    robot_dir = os.path.join(work, "robot")
    os.makedirs(robot_dir)
    for name in os.listdir(os.path.dirname(robot_file)):  # the robot file with its compliance table
        if name.endswith((".json", ".csv")):
            shutil.copy2(os.path.join(os.path.dirname(robot_file), name), robot_dir)
    robot_file = os.path.join(robot_dir, os.path.basename(robot_file))
    shutil.copy2(job, work)
    job = os.path.join(work, os.path.basename(job))
config, out = os.path.join(work, "config"), os.path.join(work, "out")
result = subprocess.run([stiffpath, "linuxcnc", "config", "--robot", robot_file, "-o", config], capture_output=True, text=True,
                        env=env)
if result.returncode != 0:
    sys.exit("FAIL: stiffpath linuxcnc config: " + result.stderr)
os.makedirs(out)
command = [stiffpath, "linuxcnc", "run", config, job, "--record", os.path.join(out, "record.csv")]
if os.getuid() == 0:
    os.chown(out, user.pw_uid, user.pw_gid)
    command = ["runuser", "-u", USER, "--", "env", "LD_LIBRARY_PATH=" + env["LD_LIBRARY_PATH"]] + command
result = subprocess.run(command, capture_output=True, text=True, timeout=600, cwd=out, env=env)
print(" ".join(command))
print(result.stdout + result.stderr)
if result.returncode != 0:
    sys.exit("FAIL: stiffpath linuxcnc run as a user exited with %d" % result.returncode)
check("runs as user" not in result.stderr, "run by a user, LinuxCNC runs as that user without a word about root")

rows = read_record(os.path.join(out, "record.csv"))
period_s = 0.0005
check(len(rows) > 1000, "%d periods recorded" % len(rows))
check(all(abs(b["t_s"] - a["t_s"] - period_s) < 1e-7 for a, b in zip(rows, rows[1:])), "one row per 0.5 ms servo period")
late = check_laser_edges(check, rows, [((-40, 170), (-40, 170), 1.0)], "as " + (USER if os.getuid() == 0 else "this user"))
robot = FiveBar(robot_file)
corrections = []
for r in rows:
    p = robot.forward_mm(r["theta1_rad"], r["theta2_rad"], (r["x_mm"], r["y_mm"]))
    corrections.append(math.hypot(p[0] - r["x_mm"], p[1] - r["y_mm"]) * 1e3)
check(10 < max(corrections) < 200, "the commands are the planned points moved by up to %.1f um" % max(corrections))
check(corrections[0] < 1e-3 and corrections[-1] < 1e-3, "at rest, before and after the job, no correction")
print("laser edges at most %d period from the square's corner; largest correction %.1f um" % (late, max(corrections)))
if not check.failures:
    shutil.rmtree(work, ignore_errors=True)
print("FAILED %d checks" % len(check.failures) if check.failures else "PASS")
sys.exit(1 if check.failures else 0)
