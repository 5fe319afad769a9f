#!/usr/bin/env python3
"""Writes asym_displacements.csv: what a compliance campaign on the robot of asym_5bar.json would measure
if its compliance were the known field below, with the CMM's noise.

The field follows the five-bar's statics: a force F at the end point C splits into the axial forces of the
two distal links, F = f1*u1 + f2*u2 (u_i the unit vector from elbow B_i to C), and the platform moves by
C(p) F with C(p) = U^-T D(p) U^-1, U = [u1 u2], D symmetric and linear over the measured rectangle
(docs/compliance.md). The elbows come from the robot's working mode (elbows [+1, -1]): each elbow is the
intersection of the proximal and distal circles on its side of the line from its actuator to C.

Grid: x = -60, -20, 20, 60 mm; y = 170, 210, 250 mm. Loads +x and -y, 50 ... 200 N in four steps.
Noise: seeded Gaussian, sigma = 3 um on each of dx and dy (numpy's default_rng(5)).
Usage: /usr/bin/python3 make_asym_table.py [--exact]  (--exact: no noise)
"""
import math
import sys

import numpy as np

ACTUATORS = [np.array([-0.040, 0.0]), np.array([0.040, 0.0])]
PROXIMAL, DISTAL, ELBOWS = [0.120, 0.130], [0.180, 0.170], [1, -1]
XS, YS = [-0.060, -0.020, 0.020, 0.060], [0.170, 0.210, 0.250]
X_MIN, X_MAX, Y_MIN, Y_MAX = -0.060, 0.060, 0.170, 0.250


def elbow(i, c):
    """B_i: the proximal circle about A_i meets the distal circle about C, on the working mode's side."""
    a, lp, ld = ACTUATORS[i], PROXIMAL[i], DISTAL[i]
    d = c - a
    dist = np.linalg.norm(d)
    along = (dist * dist + lp * lp - ld * ld) / (2 * dist)
    half = math.sqrt(lp * lp - along * along)
    unit = d / dist
    left = np.array([-unit[1], unit[0]])  # counter-clockwise of A_i -> C
    return a + along * unit + ELBOWS[i] * half * left


def link_compliance(c):
    """D(p) in m/N, linear in the coordinates normalised to the measured rectangle."""
    X = (2 * c[0] - X_MIN - X_MAX) / (X_MAX - X_MIN)
    Y = (2 * c[1] - Y_MIN - Y_MAX) / (Y_MAX - Y_MIN)
    d11 = 0.90 + 0.15 * X - 0.10 * Y
    d12 = 0.12 + 0.04 * X + 0.03 * Y
    d22 = 1.10 - 0.12 * X + 0.18 * Y
    return np.array([[d11, d12], [d12, d22]]) * 1e-6


def compliance(c):
    u = [(c - elbow(i, c)) / DISTAL[i] for i in range(2)]
    U = np.column_stack(u)
    Ui = np.linalg.inv(U)
    return Ui.T @ link_compliance(c) @ Ui


def main():
    exact = "--exact" in sys.argv
    rng = np.random.default_rng(5)
    lines = ["point,x_mm,y_mm,direction,F_N,dx_mm,dy_mm"]
    for i, x in enumerate(XS):
        for j, y in enumerate(YS):
            c = np.array([x, y])
            C = compliance(c)
            for direction, unit in (("+x", np.array([1.0, 0.0])), ("-y", np.array([0.0, -1.0]))):
                for force in (50.0, 100.0, 150.0, 200.0):
                    d = C @ (force * unit)
                    if not exact:
                        d = d + rng.normal(0.0, 3e-6, 2)
                    lines.append(f"p{i + 1}{j + 1},{x * 1e3:.3f},{y * 1e3:.3f},{direction},{force:.1f},"
                                 f"{d[0] * 1e3:.6f},{d[1] * 1e3:.6f}")
    with open("asym_displacements.csv", "w", encoding="ascii") as out:
        out.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
