# Planning and compensation from Python against `stiffpath run`'s joint file for the thesis's y motion, and against
# the compensation identities of thesis fig. 4.3 (F = -m a, Δ = C(p) F, p_cmd = p - Δ, θ = IK(p_cmd)).
import csv
import json
import threading

import numpy as np
import pytest

import stiffpath
from conftest import EXAMPLES

Y_MOTION = EXAMPLES / "y_motion.gcode"
G = 9.80665


@pytest.fixture(scope="module")
def robot():
    return stiffpath.Robot("oc-gu")


@pytest.fixture(scope="module")
def trajectory():
    return stiffpath.plan(file=str(Y_MOTION))


def read_joint_csv(path):
    with open(path) as f:
        assert f.readline().startswith("# stiffpath joints")  # the robot and rate the file was made for
        rows = list(csv.DictReader(f))
    return {key: np.array([float(r[key]) for r in rows]) for key in rows[0]}


def test_plan_moves_along_the_y_line_within_the_limits(trajectory):
    p, v, a, j = trajectory["p_m"], trajectory["v_m_s"], trajectory["a_m_s2"], trajectory["j_m_s3"]
    np.testing.assert_allclose(p[0], [0.222132, -0.075], atol=1e-12)
    np.testing.assert_allclose(p[-1], [0.222132, 0.075], atol=1e-12)
    np.testing.assert_allclose(p[:, 0], 0.222132, atol=1e-12)
    assert np.all(np.diff(trajectory["t_s"]) == pytest.approx(1 / 2000))
    assert np.max(np.linalg.norm(a, axis=1)) <= 5 * G * (1 + 1e-9)
    assert np.max(np.linalg.norm(j, axis=1)) <= 5 * G / 0.005 * (1 + 1e-9)
    # v is the derivative of p (trapezoid rule over the 2 kHz samples).
    dt = 1 / 2000
    np.testing.assert_allclose(np.diff(p[:, 1]), dt * (v[1:, 1] + v[:-1, 1]) / 2, atol=2e-7)
    assert trajectory["laser"].any() and set(np.unique(trajectory["line"])) >= {7}


def test_gcode_errors_carry_the_line():
    with pytest.raises(stiffpath.Error) as raised:
        stiffpath.plan(gcode="G21 G90\nG1 X222 Y0 F6000\nG1 X230 Q7\n")
    assert raised.value.line == 3
    assert "<gcode>:3" in str(raised.value)
    with pytest.raises(ValueError):
        stiffpath.plan()


def assert_joints_equal_the_file(joints, ref):
    assert len(joints) == len(ref["t_s"])
    np.testing.assert_allclose(joints["t_s"], ref["t_s"], atol=1e-6)
    np.testing.assert_allclose(joints["q_rad"][:, 0], ref["theta1_rad"], atol=1e-9)
    np.testing.assert_allclose(joints["q_rad"][:, 1], ref["theta2_rad"], atol=1e-9)
    np.testing.assert_allclose(joints["qd_rad_s"][:, 0], ref["omega1_rad_s"], atol=1e-9)
    np.testing.assert_allclose(joints["qdd_rad_s2"][:, 1], ref["alpha2_rad_s2"], atol=1e-6)
    np.testing.assert_allclose(joints["command_m"] * 1e3, np.stack([ref["xcmd_mm"], ref["ycmd_mm"]], 1), atol=1e-6)
    np.testing.assert_allclose(joints["force_N"], np.stack([ref["fx_n"], ref["fy_n"]], 1), atol=1e-4)
    np.testing.assert_allclose(joints["power"], ref["power"], atol=1e-6)
    np.testing.assert_array_equal(joints["laser"], ref["laser"] == 1)


def test_compensate_equals_the_cli_joint_file(robot, trajectory, cli, tmp_path):
    # The defaults are run's: dynamic compensation of a reference smoothed by two 4 ms moving averages, which
    # hold 8 samples each at 2 kHz and so lengthen the job by 16 samples.
    compensator = stiffpath.Compensator(robot)
    assert compensator.method == "dynamic"
    assert len(compensator.compensate(trajectory)) == len(trajectory) + 2 * round(0.004 * 2000)
    # The main job itself (planned with its path, so the filters retime the path as run's do).
    joints, summary = stiffpath.run(file=str(Y_MOTION), robot=robot)
    assert summary["method"] == "dynamic" and summary["smooth_s"] == pytest.approx(0.008)
    out = tmp_path / "joints.csv"
    cli("run", Y_MOTION, "-o", out)
    assert_joints_equal_the_file(joints, read_joint_csv(out))


@pytest.mark.parametrize("options, flags", [
    ({"method": "quasi-static", "smooth_s": 0.0}, ["--compensation", "quasi-static", "--smooth-ms", "0"]),
    ({"method": "dynamic", "damping_ratio": 0.1, "smooth_s": 0.004, "shaper": "zv"},
     ["--damping-ratio", "0.1", "--smooth-ms", "4", "--shaper", "zv"]),
])
def test_compensation_options_equal_the_cli_flags(robot, trajectory, cli, tmp_path, options, flags):
    joints, _ = stiffpath.run(file=str(Y_MOTION), robot=robot, method=options.pop("method"),
                              damping_ratio=options.pop("damping_ratio", 0.05), **options)
    out = tmp_path / "joints.csv"
    cli("run", Y_MOTION, "-o", out, *flags)
    assert_joints_equal_the_file(joints, read_joint_csv(out))


def test_quasi_static_compensation_follows_fig_4_3(robot, trajectory):
    compensator = stiffpath.Compensator(robot, method="quasi-static")
    joints = compensator.compensate(trajectory, smooth_s=0.0)
    assert len(joints) == len(trajectory)
    np.testing.assert_allclose(joints["force_N"], -robot.moving_mass_kg * trajectory["a_m_s2"], rtol=1e-12, atol=1e-12)
    delta = compensator.model.predict(trajectory["p_m"], joints["force_N"])
    np.testing.assert_allclose(joints["deflection_m"], delta, atol=1e-15)
    np.testing.assert_allclose(joints["command_m"], trajectory["p_m"] - delta, atol=1e-15)
    np.testing.assert_allclose(joints["q_rad"], robot.ik(joints["command_m"]), atol=1e-12)
    assert np.max(np.linalg.norm(delta, axis=1)) > 100e-6  # 5 g on 3.6 kg deflects the OC robot by tenths of a mm
    # The per-sample step gives the same command as the whole-trajectory call.
    k = len(trajectory) // 3
    s = trajectory[k]
    c = compensator.step(s["t_s"], s["p_m"], s["v_m_s"], s["a_m_s2"], s["j_m_s3"])
    assert c.ok and c.q_rad == pytest.approx(tuple(joints["q_rad"][k]), abs=1e-12)
    # Its torque feed-forward is the platform's D'Alembert load through the Jacobian at the command: τ = Jᵀ·m·a.
    J = np.asarray(robot.jacobian(c.q_rad))
    expected = J.T @ (robot.moving_mass_kg * np.asarray(s["a_m_s2"]))
    assert np.max(np.abs(expected)) > 0.1
    np.testing.assert_allclose(c.load_torque_Nm, expected, rtol=1e-9, atol=1e-12)
    # Without compensation the joints put the end point on the planned path.
    plain = stiffpath.Compensator(robot, enabled=False).compensate(trajectory, smooth_s=0.0)
    np.testing.assert_allclose(robot.fk(plain["q_rad"]), trajectory["p_m"], atol=1e-12)


def test_a_refused_step_reports_instead_of_raising(robot):
    c = stiffpath.Compensator(robot).step(0.0, (0.299, 0.0))
    assert not c.ok and c.status != "ok"


def test_long_calls_release_the_gil():
    results = []

    def work():
        results.append(len(stiffpath.plan(file=str(Y_MOTION))))

    threads = [threading.Thread(target=work) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(set(results)) == 1 and results[0] > 0


def test_the_robot_files_damping_ratio_is_the_compensators_default(tmp_path):
    doc = stiffpath.Robot("oc-gu").to_dict()
    assert doc["tip_damping_ratio"] == pytest.approx(0.05)
    doc["tip_damping_ratio"] = 0.15
    path = tmp_path / "damped.json"
    path.write_text(json.dumps(doc))
    damped = stiffpath.Robot(str(path))
    assert damped.tip_damping_ratio == pytest.approx(0.15)
    assert stiffpath.Compensator(damped).damping_ratio == pytest.approx(0.15)
    assert stiffpath.Compensator(damped, damping_ratio=0.3).damping_ratio == pytest.approx(0.3)
    assert stiffpath.Compensator(stiffpath.Robot("oc-gu")).damping_ratio == pytest.approx(0.05)
