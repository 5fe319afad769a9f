#!/usr/bin/python3
"""The thesis's y-line comparison (fig. 4.7a, §4.7): plan the 150 mm line along y at 5 g, run it without
compensation, with the thesis's quasi-static compensation and with `stiffpath run`'s default (dynamic, smoothed),
mark each with the digital twin and plot each mark's deviation from its fitted line.
Usage: PYTHONPATH=build/dev/python /usr/bin/python3 examples/python/y_line.py [out.png]"""
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import stiffpath

robot = stiffpath.Robot("oc-gu")
trajectory = stiffpath.plan(file=str(Path(__file__).resolve().parents[1] / "y_motion.gcode"))
variants = [("without compensation", dict(enabled=False)),
            ("quasi-static (thesis)", dict(method="quasi-static")),
            ("dynamic (run's default)", dict(method="dynamic"))]
fig, ax = plt.subplots(figsize=(8, 4))
for label, options in variants:
    joints = stiffpath.Compensator(robot, **options).compensate(trajectory)
    run = stiffpath.simulate(robot, joints)
    m = run.metrics
    mark = run.marked_m
    x_fit = np.polyval(np.polyfit(mark[:, 1], mark[:, 0], 1), mark[:, 1])  # the line x(y) through the mark
    ax.plot(mark[:, 1] * 1e3, (mark[:, 0] - x_fit) * 1e6,
            label=f"{label}: area {m.deviation_area_m2 * 1e6:.4f} mm², max {m.max_deviation_m * 1e6:.1f} µm")
    print(f"{label:24s} length {m.length_m * 1e3:.4f} mm  deviation area {m.deviation_area_m2 * 1e6:.4f} mm^2  "
          f"max deviation {m.max_deviation_m * 1e6:.1f} um  peak deflection {m.peak_deflection_m * 1e6:.0f} um")
ax.set(xlabel="y (mm)", ylabel="deviation from the fitted line (µm)", title=f"y line at 5 g, robot {robot.name}")
ax.legend(fontsize=8)
fig.tight_layout()
out = sys.argv[1] if len(sys.argv) > 1 else "y_line.png"
fig.savefig(out, dpi=120)
print("wrote", out)
