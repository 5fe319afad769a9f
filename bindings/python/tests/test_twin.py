# The digital twin and path metrics from Python against `stiffpath simulate` on the same joints, and on lines whose
# metrics are known by construction.
import numpy as np
import pytest

import stiffpath
from conftest import EXAMPLES


def test_simulate_equals_the_cli_and_compensation_straightens_the_line(cli, tmp_path):
    robot = stiffpath.Robot("oc-gu")
    trajectory = stiffpath.plan(file=str(EXAMPLES / "y_motion.gcode"))
    compensated = stiffpath.Compensator(robot).compensate(trajectory)
    plain = stiffpath.Compensator(robot, enabled=False).compensate(trajectory)
    run = stiffpath.simulate(robot, compensated)
    metrics = stiffpath.run_metrics(run, sides=1)
    joints = tmp_path / "joints.csv"
    cli("run", EXAMPLES / "y_motion.gcode", "-o", joints)
    doc = cli("simulate", joints, "--json")
    assert metrics.length_m * 1e3 == pytest.approx(doc["length_mm"], abs=1e-4)
    assert metrics.max_deviation_m * 1e3 == pytest.approx(doc["max_deviation_mm"], abs=1e-4)
    assert run.marked_m.shape == (doc["marked_points"], 2)
    without = stiffpath.run_metrics(stiffpath.simulate(robot, plain), sides=1)
    assert metrics.max_deviation_m < without.max_deviation_m


def test_true_compliance_differs_from_the_model_by_at_most_the_perturbation():
    robot = stiffpath.Robot("oc-gu")
    base = stiffpath.true_compliance(robot, perturbation=0.0)
    truth = stiffpath.true_compliance(robot, perturbation=0.1, seed=3)
    x, y = np.meshgrid(np.linspace(0.175, 0.27, 5), np.linspace(-0.07, 0.07, 5))
    ratio = truth.C(x, y)[..., 0, 0] / base.C(x, y)[..., 0, 0]  # C_true = S C S: Cxx scaled by sx in [0.9, 1.1]
    assert np.all((ratio > 0.9 - 1e-9) & (ratio < 1.1 + 1e-9)) and np.ptp(ratio) > 0


def test_path_metrics_of_a_straight_and_a_bent_line():
    t = np.linspace(0.0, 0.1, 2001)
    straight = np.stack([0.2 + 0 * t, t - 0.05], axis=1)
    m = stiffpath.path_metrics(straight)
    assert m.length_m == pytest.approx(0.1, abs=1e-5)
    assert m.max_deviation_m < 1e-9 and len(m.sides) == 1
    bump = straight.copy()
    bump[:, 0] += 20e-6 * np.sin(2 * np.pi * t / 0.1)  # one full sine: the fitted line stays at x = 0.2
    b = stiffpath.path_metrics(bump)
    assert b.max_deviation_m == pytest.approx(20e-6, rel=0.05)
    # |u| <= A everywhere, so the area is at most A L.
    assert 0 < b.deviation_area_m2 <= 20e-6 * 0.1
