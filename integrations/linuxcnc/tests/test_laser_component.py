#!/usr/bin/python3
"""stiffpathlaser under halrun, its inputs scripted by streamer: the delay, S against s-max, M4's speed scaling, M62's
full power, no fire on rapids or at rest (LinuxCNC's wait before M3), a one-period exact-stop pause kept on and a longer
one not, and the gate acting at once. The expected outputs are computed here from the documented rules.
usage: test_laser_component.py WORK_DIR (needs the modules installed, see linuxcnc_env.sh; run as root or not)"""
import os
import shutil
import subprocess
import sys

work = sys.argv[1]
PERIOD_NS = 500000
DELAY = 2
S_MAX = 250.0
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


# Inputs per period: on, dynamic, full, s, motion_type, current_vel, requested_vel, gate.
def inputs(k):
    on, dynamic, full, s, mtype, vel, req, gate = 0, 0, 0, 0.0, 0, 0.0, 0.0, 1
    if 10 <= k < 20:      # M3 S100 while motion stands (LinuxCNC waits for the stop): no fire
        on, s = 1, 100.0
    elif 20 <= k < 60:    # the cut: M3 S100 on a feed move (motion-type a period late), an exact-stop corner at 40
        on, s, mtype, vel, req = 1, 100.0, 0 if k == 20 else 2, 0.0 if k == 40 else 500.0, 1000.0
    elif 60 <= k < 70:    # at rest at the end, motion-type still 2 for two periods, then idle
        on, s, mtype = 1, 100.0, 2 if k < 62 else 0
    elif 70 <= k < 90:    # M4 S500 (power 1 after clamping S/s-max = 2): scaled by vel/req
        on, dynamic, s, mtype, vel, req = 1, 1, 500.0, 2, 10.0 * (k - 70), 100.0
    elif 90 <= k < 100:   # a rapid with the laser on: no fire
        on, s, mtype, vel, req = 1, 100.0, 1, 800.0, 800.0
    elif 100 <= k < 120:  # M62 after the rapid, motion-type still 1 in its first period: full power whatever S; a
        # pause of three periods at 110..112 switches it off
        full, mtype, vel, req = 1, 1 if k == 100 else 2, 0.0 if 110 <= k < 113 else 300.0, 300.0
    elif 120 <= k < 130:  # the gate drops (a fault) in the middle of a cut
        on, s, mtype, vel, req, gate = 1, 200.0, 3, 300.0, 300.0, 0 if k >= 125 else 1
    return on, dynamic, full, s, mtype, vel, req, gate


END = 140


def requested(k, newest):  # the power period k cuts with, and whether the tool moves; motion-type read a period later
    on, dynamic, full, s, _, vel, req, gate = inputs(k)
    mtype = inputs(min(k + 1, newest))[4]
    p = 1.0 if full else (min(1.0, s / S_MAX) if on else 0.0)
    if dynamic and not full:
        p *= min(1.0, vel / req) if req > 0 else 0.0
    return (p if mtype != 1 else 0.0), vel > 0


def expected(k):
    fired = [False] * (END + DELAY + 1)
    out = []
    for j in range(END):
        src = j - DELAY
        if src < 0:
            out.append((0, 0.0))
            continue
        p, moving = requested(src, j)
        fire = p > 0 and moving
        if not fire and p > 0 and src > 0 and fired[src - 1]:  # a pause of at most DELAY periods within a cut
            fire = any(requested(src + i, j)[0] > 0 and requested(src + i, j)[1] for i in range(1, DELAY + 1))
        fired[src] = fire
        gate = inputs(j)[7]
        out.append((1, p) if fire and gate else (0, 0.0))
    return out[k]


shutil.rmtree(work, ignore_errors=True)
os.makedirs(os.path.join(work, "home"))
with open(os.path.join(work, "inputs.stream"), "w") as f:
    for k in range(END):
        on, dynamic, full, s, mtype, vel, req, gate = inputs(k)
        f.write("%d %d %d %d %.17g %d %.17g %.17g %d\n" % (k + 1, on, dynamic, full, s, mtype, vel, req, gate))
with open(os.path.join(work, "laser.hal"), "w") as f:
    f.write("""loadrt threads name1=servo-thread period1=%d fp1=1
loadrt streamer depth=%d cfg=ubbbfsffb
loadrt stiffpathlaser
loadrt sampler depth=%d cfg=ubf
setp stiffpathlaser.s-max %g
addf streamer.0 servo-thread
addf stiffpathlaser servo-thread
addf sampler.0 servo-thread
net k streamer.0.pin.0 => sampler.0.pin.0
net on streamer.0.pin.1 => stiffpathlaser.on
net dynamic streamer.0.pin.2 => stiffpathlaser.dynamic
net full streamer.0.pin.3 => stiffpathlaser.full
net s streamer.0.pin.4 => stiffpathlaser.s
net mtype streamer.0.pin.5 => stiffpathlaser.motion-type
net vel streamer.0.pin.6 => stiffpathlaser.current-vel
net req streamer.0.pin.7 => stiffpathlaser.requested-vel
net gate streamer.0.pin.8 => stiffpathlaser.gate
net laser stiffpathlaser.laser => sampler.0.pin.1
net power stiffpathlaser.power => sampler.0.pin.2
loadusr -w halstreamer inputs.stream
start
loadusr -w halsampler -n %d record.txt
""" % (PERIOD_NS, END + 10, END + 100, S_MAX, END + 40))
env = dict(os.environ, HOME=os.path.join(work, "home"), RTAPI_FIFO_PATH=os.path.join(work, "rtapi_fifo"))
if os.getuid() == 0:
    env["RTAPI_UID"] = env.get("RTAPI_UID", "65534")
    for root, dirs, files in os.walk(work):
        for name in dirs + files + [""]:
            os.chown(os.path.join(root, name), int(env["RTAPI_UID"]), -1)
result = subprocess.run(["halrun", "-f", "laser.hal"], cwd=work, env=env, capture_output=True, text=True, timeout=120)
if result.returncode != 0:
    sys.exit("FAIL: halrun: " + result.stderr[-2000:])

rows = {}
with open(os.path.join(work, "record.txt")) as f:
    for line in f:
        v = line.split()
        k = int(v[0]) - 1
        if k >= 0 and k not in rows:  # the stream's last line is held once it has run dry
            rows[k] = (int(v[1]), float(v[2]))
check(sorted(rows) == list(range(END)), "every input line was played once")
for k in range(END):
    want = expected(k)
    got = rows.get(k, (None, None))
    check(got[0] == want[0] and abs(got[1] - want[1]) <= 1e-6,
          "period %d: laser %s power %s, expected %d %g" % (k, got[0], got[1], want[0], want[1]))
# The rules, not only the model above: named periods.
check(all(rows[k][0] == 0 for k in range(10, 20 + DELAY)), "no fire while motion stands with M3 on, nor before the delay")
check(rows[20 + DELAY] == (1, 0.4), "the cut starts DELAY periods after the tool moves, at S/s-max = 0.4")
check(rows[40 + DELAY] == (1, 0.4), "the exact-stop corner (one period at rest) keeps the laser on")
check(rows[60 + DELAY][0] == 0, "at rest at the end the laser goes off at once, though motion-type is still 2")
check(abs(rows[75 + DELAY][1] - 0.5) <= 1e-6, "M4: power x vel / requested-vel (50 / 100)")
check(all(rows[k][0] == 0 for k in range(90 + DELAY, 100 + DELAY)), "no fire on a rapid")
check(rows[100 + DELAY] == (1, 1.0) and rows[105 + DELAY] == (1, 1.0),
      "M62: full power from the move's first period, though motion-type still says rapid there")
check(rows[89 + DELAY][0] == 0 and rows[88 + DELAY][0] == 1, "the cut's last period before the rapid, by the next motion-type")
check(all(rows[k][0] == 0 for k in range(110 + DELAY, 113 + DELAY)), "a pause of three periods switches it off")
check(rows[124][0] == 1 and rows[125][0] == 0, "the gate acts in the period it drops, without the delay")
shutil.rmtree(work, ignore_errors=True)
print("FAILED %d checks" % len(failures) if failures else "PASS")
sys.exit(1 if failures else 0)
