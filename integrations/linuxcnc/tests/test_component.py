#!/usr/bin/python3
"""stiffpathcomp's behaviour around the step, under halrun with a scripted Cartesian command (streamer) and a
simulated drive: pass-through while disabled, the blend's delayed ramp, the correction taken back out of the
feedback, the load-torque feed-forward, the hold and fault on a refused step, and the fresh start after a reset.
usage: test_component.py WORK_DIR (needs the modules installed, see linuxcnc_env.sh; run as root or not)"""
import math
import os
import shutil
import subprocess
import sys

work = sys.argv[1]
PERIOD_NS = 500000
T = PERIOD_NS * 1e-9
RAMP_S = 0.01
L_M = 0.150
ENABLE_AT, MOVE_FROM, MOVE_TO, JUMP_AT, JUMP_END, RESET_AT, END = 50, 100, 300, 320, 330, 360, 420
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def ik_deg(x_mm, y_mm):  # eq. 2.2, working mode theta1 = phi + eta
    r = math.hypot(x_mm, y_mm) * 1e-3
    phi, eta = math.atan2(y_mm, x_mm), math.acos(min(1.0, r / (2 * L_M)))
    return math.degrees(phi + eta), math.degrees(phi - eta)


def cartesian(k):
    if MOVE_FROM <= k < MOVE_TO:  # 5 mm of cosine in x every 0.1 s: about 1 g
        t = (k - MOVE_FROM) * T
        return 222.132 + 5.0 * (1 - math.cos(2 * math.pi * t / 0.1)) / 2, 0.0
    if JUMP_AT <= k < JUMP_END:  # far outside the reach: the step must refuse
        return 400.0, 0.0
    return 222.132, 0.0


shutil.rmtree(work, ignore_errors=True)
os.makedirs(os.path.join(work, "home"))
with open(os.path.join(work, "commands.stream"), "w") as f:
    for k in range(END):
        x, y = cartesian(k)
        q = ik_deg(min(x, 290.0), y)
        f.write("%d %.17g %.17g %.17g %.17g %d %d\n" % (k + 1, x, y, q[0], q[1], k >= ENABLE_AT, k == RESET_AT))
with open(os.path.join(work, "component.hal"), "w") as f:
    f.write("""loadrt threads name1=servo-thread period1=%d fp1=1
loadrt streamer depth=%d cfg=uffffbb
loadrt stiffpathcomp robot=oc-gu model=thesis-oc
loadrt sampler depth=%d cfg=uffffffbsufff
setp stiffpathcomp.ramp-time %g
addf streamer.0 servo-thread
addf stiffpathcomp servo-thread
addf sampler.0 servo-thread
net k streamer.0.pin.0 => sampler.0.pin.0
net x streamer.0.pin.1 => stiffpathcomp.x-cmd
net y streamer.0.pin.2 => stiffpathcomp.y-cmd
net in0 streamer.0.pin.3 => stiffpathcomp.joint.0.cmd-in
net in1 streamer.0.pin.4 => stiffpathcomp.joint.1.cmd-in
net enable streamer.0.pin.5 => stiffpathcomp.enable
net reset streamer.0.pin.6 => stiffpathcomp.reset
net out0 stiffpathcomp.joint.0.cmd-out => stiffpathcomp.joint.0.fb-in sampler.0.pin.1
net out1 stiffpathcomp.joint.1.cmd-out => stiffpathcomp.joint.1.fb-in sampler.0.pin.2
net fb0 stiffpathcomp.joint.0.fb-out => sampler.0.pin.3
net fb1 stiffpathcomp.joint.1.fb-out => sampler.0.pin.4
net corr0 stiffpathcomp.joint.0.correction-deg => sampler.0.pin.5
net corr1 stiffpathcomp.joint.1.correction-deg => sampler.0.pin.6
net fault stiffpathcomp.fault => sampler.0.pin.7
net status stiffpathcomp.status => sampler.0.pin.8
net refusals stiffpathcomp.refusals => sampler.0.pin.9
net blend stiffpathcomp.blend => sampler.0.pin.10
net tau0 stiffpathcomp.joint.0.load-torque-nm => sampler.0.pin.11
net tau1 stiffpathcomp.joint.1.load-torque-nm => sampler.0.pin.12
loadusr -w halstreamer commands.stream
start
loadusr -w halsampler -n %d record.txt
""" % (PERIOD_NS, END + 10, END + 100, RAMP_S, END + 40))
env = dict(os.environ, HOME=os.path.join(work, "home"), RTAPI_FIFO_PATH=os.path.join(work, "rtapi_fifo"))
if os.getuid() == 0:
    env["RTAPI_UID"] = env.get("RTAPI_UID", "65534")
    for root, dirs, files in os.walk(work):
        for name in dirs + files + [""]:
            os.chown(os.path.join(root, name), int(env["RTAPI_UID"]), -1)
result = subprocess.run(["halrun", "-f", "component.hal"], cwd=work, env=env, capture_output=True, text=True, timeout=120)
if result.returncode != 0:
    sys.exit("FAIL: halrun: " + result.stderr[-2000:])

rows = {}
with open(os.path.join(work, "record.txt")) as f:
    for line in f:
        v = line.split()
        k = int(v[0]) - 1
        if k >= 0 and k not in rows:  # the stream's last line is held once it has run dry
            rows[k] = dict(out=(float(v[1]), float(v[2])), fb=(float(v[3]), float(v[4])), corr=(float(v[5]), float(v[6])),
                           fault=v[7] == "1", status=int(v[8]), refusals=int(v[9]), blend=float(v[10]),
                           tau=(float(v[11]), float(v[12])))
check(sorted(rows) == list(range(END)), "every command was played once")
cmd_in = {k: ik_deg(min(cartesian(k)[0], 290.0), 0.0) for k in range(END)}
EPS = 2e-6  # halsampler prints six decimals


def close(a, b):
    return all(abs(u - v) <= EPS for u, v in zip(a, b))


for k in range(ENABLE_AT):
    r = rows[k]
    check(close(r["out"], cmd_in[k]) and r["blend"] == 0 and not r["fault"], "period %d: disabled, passes through" % k)
for k in range(ENABLE_AT, MOVE_FROM):
    expected = min(1.0, max(0.0, (k - (ENABLE_AT + 3)) * T / RAMP_S))
    check(abs(rows[k]["blend"] - expected) <= EPS, "period %d: blend %g, expected %g (ramp from the 5th enabled period)"
          % (k, rows[k]["blend"], expected))
largest = 0.0
for k in range(ENABLE_AT, JUMP_AT):
    r = rows[k]
    check(close(r["out"], (cmd_in[k][0] + r["corr"][0], cmd_in[k][1] + r["corr"][1])), "period %d: out = in + correction" % k)
    check(close(r["fb"], cmd_in[k]), "period %d: the feedback has the correction taken out" % k)
    check(not r["fault"] and r["status"] == 0, "period %d: no refusal" % k)
    largest = max(largest, abs(r["corr"][0]), abs(r["corr"][1]))
check(largest > 0.005, "the 1 g motion is corrected (largest correction %g degree)" % largest)
held = rows[JUMP_AT - 1]
for k in range(JUMP_AT, RESET_AT):
    r = rows[k]
    check(r["fault"] and r["status"] != 0 and r["refusals"] == 1, "period %d: fault, a status, one refusal" % k)
    check(r["out"] == held["out"], "period %d: the last good command is held" % k)
    check(close(r["fb"], (r["out"][0] - held["corr"][0], r["out"][1] - held["corr"][1])),
          "period %d: the feedback keeps the last correction" % k)
for k in range(RESET_AT, END):
    r = rows[k]
    expected = min(1.0, max(0.0, (k - (RESET_AT + 3)) * T / RAMP_S))
    check(not r["fault"] and r["refusals"] == 1 and abs(r["blend"] - expected) <= EPS, "period %d: reset, ramping afresh" % k)
    check(close(r["out"], cmd_in[k]), "period %d: at rest after the reset, out = in" % k)


def load_torque_Nm(j):  # tau = J^T m a at c[j], a the centred second difference; J = (d theta / d p)^-1 by differences
    (x0, y0), (x1, y1), (x2, y2) = cartesian(j - 1), cartesian(j), cartesian(j + 1)
    F = (3.6 * (x2 - 2 * x1 + x0) * 1e-3 / T**2, 3.6 * (y2 - 2 * y1 + y0) * 1e-3 / T**2)  # m a, thesis §4.2 mass
    h = 1e-4  # mm
    a, c = [(u - v) / (2 * h * 1e-3) for u, v in zip(ik_deg(x1 + h, y1), ik_deg(x1 - h, y1))]
    b, d = [(u - v) / (2 * h * 1e-3) for u, v in zip(ik_deg(x1, y1 + h), ik_deg(x1, y1 - h))]
    a, b, c, d = (math.radians(u) for u in (a, b, c, d))  # rad/m: [[a, b], [c, d]] = J^-1
    det = a * d - b * c
    J = ((d / det, -b / det), (-c / det, a / det))
    return tuple(J[0][i] * F[0] + J[1][i] * F[1] for i in range(2))


largest_tau = 0.0
for k in range(MOVE_FROM, JUMP_AT - 1):
    if rows[k - 3]["blend"] == 0.0:
        continue
    t = [load_torque_Nm(j) for j in (k - 1, k - 2, k - 3)]
    expected = tuple((t[2][i] + 4 * t[1][i] + t[0][i]) / 6 for i in range(2))
    got = rows[k]["tau"]
    check(all(abs(g - e) <= 2e-3 * abs(e) + 1e-5 for g, e in zip(got, expected)),
          "period %d: load torque %s N m, expected J^T m a = %s" % (k, got, expected))
    largest_tau = max(largest_tau, abs(got[0]), abs(got[1]))
check(largest_tau > 0.5, "the 1 g motion loads the drives (largest load torque %g N m)" % largest_tau)
check(all(rows[k]["tau"] == (0.0, 0.0) for k in range(JUMP_AT, RESET_AT)), "no load torque while faulted")
print("largest correction %.4f degree, largest load torque %.3f N m, refused with status %d"
      % (largest, largest_tau, rows[JUMP_AT]["status"]))
shutil.rmtree(work, ignore_errors=True)
print("FAILED %d checks" % len(failures) if failures else "PASS")
sys.exit(1 if failures else 0)
