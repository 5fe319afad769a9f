# Robot kinematics from Python against the thesis's closed form (eqs. 2.1-2.2), finite differences and the CLI.
import numpy as np
import pytest

import stiffpath

L = 0.150  # the thesis robot's four links (m)


def thesis_ik(p):
    """Eq. 2.2 by hand: C = l(e^{iθ1} + e^{iθ2}); θ1,2 = φ ± acos(r / 2l), elbows (+1, -1)."""
    r = np.hypot(p[..., 0], p[..., 1])
    phi = np.arctan2(p[..., 1], p[..., 0])
    alpha = np.arccos(r / (2 * L))
    return np.stack([phi + alpha, phi - alpha], axis=-1)


def workspace_grid():
    x, y = np.meshgrid(np.linspace(0.172132, 0.272132, 11), np.linspace(-0.075, 0.075, 7))
    return np.stack([x, y], axis=-1)  # (7, 11, 2)


def test_presets_are_the_thesis_builds():
    assert sorted(stiffpath.presets()) == ["oc-gl", "oc-gu", "sc-gl", "sc-gu"]
    robot = stiffpath.Robot("oc-gu")
    assert robot.moving_mass_kg == pytest.approx(3.6)
    assert robot.cg_height_m == pytest.approx(0.0359)


def test_ik_matches_eq_2_2_over_the_workspace_and_keeps_the_shape():
    p = workspace_grid()
    q = stiffpath.Robot("oc-gu").ik(p)
    assert q.shape == p.shape
    np.testing.assert_allclose(q, thesis_ik(p), atol=1e-12)


def test_fk_is_eq_2_1_and_inverts_ik():
    robot = stiffpath.Robot("sc-gl")
    p = workspace_grid().reshape(-1, 2)
    q = robot.ik(p)
    by_hand = L * np.stack([np.cos(q[:, 0]) + np.cos(q[:, 1]), np.sin(q[:, 0]) + np.sin(q[:, 1])], axis=-1)
    np.testing.assert_allclose(robot.fk(q), by_hand, atol=1e-15)
    np.testing.assert_allclose(robot.fk(q), p, atol=1e-12)


def test_ik_agrees_with_the_cli(cli):
    robot = stiffpath.Robot("oc-gu")
    for x_mm, y_mm in [(222.132, 37.5), (180.0, -60.0), (265.0, 70.0)]:
        doc = cli("kin", "ik", "--x-mm", x_mm, "--y-mm", y_mm, "--json")
        q = robot.ik([x_mm / 1e3, y_mm / 1e3])
        assert q == pytest.approx([doc["theta1_rad"], doc["theta2_rad"]], abs=1e-11)


def test_jacobian_matches_finite_differences():
    robot = stiffpath.Robot("oc-gu")
    q = robot.ik(workspace_grid().reshape(-1, 2))
    J = robot.jacobian(q)
    assert J.shape == (q.shape[0], 2, 2)
    h = 1e-7
    for j in range(2):
        dq = np.zeros(2)
        dq[j] = h
        numeric = (robot.fk(q + dq) - robot.fk(q - dq)) / (2 * h)
        np.testing.assert_allclose(J[:, :, j], numeric, atol=1e-8)


def test_a_refused_point_raises_an_error_naming_it():
    robot = stiffpath.Robot("oc-gu")
    p = np.array([[0.222, 0.0], [0.299, 0.0], [0.222, 0.01]])  # 299 mm: beyond 2l minus the 5 mm margin
    with pytest.raises(stiffpath.Error, match=r"p_m\[1\] \(x = 299 mm, y = 0 mm\) refused") as raised:
        robot.ik(p)
    assert isinstance(raised.value, ValueError)
    assert robot.reachable(p).tolist() == [True, False, True]
    assert "stretched" in robot.refusal(0.299, 0.0) or robot.refusal(0.299, 0.0) != ""
    assert robot.refusal(0.222, 0.0) == ""


def test_bad_shapes_and_robot_files_are_value_errors(tmp_path):
    robot = stiffpath.Robot("oc-gu")
    with pytest.raises(ValueError, match="shape"):
        robot.ik(np.zeros((4, 3)))
    bad = tmp_path / "robot.json"
    bad.write_text('{\n  "name": "x",\n  "moving_mass_kg": "heavy"\n}\n')
    with pytest.raises(stiffpath.Error) as raised:
        stiffpath.Robot(str(bad))
    assert raised.value.file == str(bad)
    assert "missing field" in raised.value.message
    assert str(raised.value).startswith(str(bad))


def test_help_texts_carry_units():
    assert "rad" in stiffpath.Robot.ik.__doc__ and " m" in stiffpath.Robot.ik.__doc__
    assert "method" in stiffpath.fit.__doc__ and "µm" in stiffpath.cv.__doc__
    assert [field for field in stiffpath.trajectory_dtype.names] == ["t_s", "p_m", "v_m_s", "a_m_s2", "j_m_s3", "laser",
                                                                     "power", "line"]
