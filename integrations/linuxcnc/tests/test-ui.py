#!/usr/bin/python3
# Headless "display" for the G-code test: starts the machine, homes it, runs a program while halsampler records,
# then writes result.txt and exits (which shuts LinuxCNC down). Arguments come from the environment.
import os
import signal
import subprocess
import sys
import time

import linuxcnc

PROGRAM = os.environ["STIFFPATH_TEST_PROGRAM"]
RECORD = os.environ["STIFFPATH_TEST_RECORD"]
RESULT = os.environ.get("STIFFPATH_TEST_RESULT", "result.txt")


def wait_for(predicate, what, timeout_s):
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        status.poll()
        if predicate():
            return
        time.sleep(0.05)
    raise RuntimeError("timed out after %.0f s waiting for %s" % (timeout_s, what))


def errors():
    messages = []
    while True:
        message = error_channel.poll()
        if not message:
            return messages
        messages.append(message[1])


command = linuxcnc.command()
status = linuxcnc.stat()
error_channel = linuxcnc.error_channel()
outcome = "failed"
try:
    wait_for(lambda: status.task_state == linuxcnc.STATE_ESTOP and status.joints == 2 and status.cycle_time > 0,
             "LinuxCNC to start", 60)
    command.state(linuxcnc.STATE_ESTOP_RESET)
    command.state(linuxcnc.STATE_ON)
    wait_for(lambda: status.task_state == linuxcnc.STATE_ON, "machine on", 10)
    command.mode(linuxcnc.MODE_MANUAL)
    command.home(-1)
    wait_for(lambda: all(status.homed[:2]), "homing", 20)
    command.teleop_enable(1)
    wait_for(lambda: status.motion_mode == linuxcnc.TRAJ_MODE_TELEOP, "world mode", 10)
    time.sleep(0.5)  # the compensation's blend factor ramps in after homing (0.1 s)

    with open(RECORD, "w") as record:
        # at most 100 s of servo periods, whatever happens to the program
        sampler = subprocess.Popen(["halsampler", "-t", "-c", "0", "-n", "200000"], stdout=record)
        time.sleep(0.3)
        subprocess.run(["halcmd", "sets", "record", "1"], check=True)
        command.mode(linuxcnc.MODE_AUTO)
        command.program_open(PROGRAM)
        command.auto(linuxcnc.AUTO_RUN, 0)
        wait_for(lambda: status.exec_state != linuxcnc.EXEC_DONE or status.interp_state != linuxcnc.INTERP_IDLE,
                 "the program to start", 10)
        wait_for(lambda: status.interp_state == linuxcnc.INTERP_IDLE and status.exec_state == linuxcnc.EXEC_DONE
                 and status.inpos, "the program to finish", 60)
        time.sleep(0.2)
        subprocess.run(["halcmd", "sets", "record", "0"], check=True)
        time.sleep(0.5)  # let halsampler drain the FIFO
        sampler.send_signal(signal.SIGINT)
        sampler.wait(timeout=10)
    problems = errors()
    outcome = "ok" if not problems else "errors: " + " | ".join(problems)
except Exception as exception:  # report every failure through the result file, then shut down
    outcome = "failed: %s; errors: %s" % (exception, " | ".join(errors()))
with open(RESULT, "w") as result:
    result.write(outcome + "\n")
sys.exit(0 if outcome == "ok" else 1)
