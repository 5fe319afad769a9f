# One job through every surface (CLI, C, Python, MATLAB/Octave) gives identical joint commands: one JobSpec underneath.
import os
import shutil
import subprocess

import numpy as np
import pytest

import stiffpath
from conftest import EXAMPLES, SOURCE_DIR

ROBOT = str(SOURCE_DIR / "examples" / "robots" / "asym_5bar.json")
JOB = str(SOURCE_DIR / "examples" / "robots" / "asym_square.gcode")
COLUMNS = ["t_s", "theta1_rad", "theta2_rad", "omega1_rad_s", "omega2_rad_s", "alpha1_rad_s2", "alpha2_rad_s2",
           "laser", "power", "line"]

# The binary joint file, version 2 (docs/compensation.md): a 128-byte header, 120-byte little-endian records.
RECORD = np.dtype([("t_s", "<f8"), ("q", "<f8", 2), ("qd", "<f8", 2), ("qdd", "<f8", 2), ("p", "<f8", 2),
                   ("p_cmd", "<f8", 2), ("F", "<f8", 2), ("power", "<f8"), ("line", "<i4"), ("laser", "u1"),
                   ("pad", "u1", 3)])


def from_cli(cli, tmp_path, *flags):
    out = tmp_path / "cli.bin"
    cli("run", JOB, "--robot", ROBOT, "--format", "bin", "-o", out, *flags)
    r = np.fromfile(out, dtype=RECORD, offset=128)
    return np.column_stack([r["t_s"], r["q"], r["qd"], r["qdd"], r["laser"], r["power"], r["line"]])


def from_python(**options):
    joints, summary = stiffpath.run(file=JOB, robot=ROBOT, **options)
    return np.column_stack([joints["t_s"], joints["q_rad"], joints["qd_rad_s"], joints["qdd_rad_s2"], joints["laser"],
                            joints["power"], joints["line"]]), summary


def from_c(tmp_path, mode):
    program = os.environ.get("STIFFPATH_C_RUN_JOB")
    if not program:
        pytest.skip("STIFFPATH_C_RUN_JOB not set (run through ctest)")
    out = tmp_path / "c.csv"
    subprocess.run([program, ROBOT, JOB, out] + ([mode] if mode else []), check=True)
    return np.loadtxt(out, delimiter=",", skiprows=1)


def from_octave(tmp_path, options):
    mex_dir = os.environ.get("STIFFPATH_MEX_DIR")
    octave = shutil.which("octave-cli") or shutil.which("octave")
    if not mex_dir or not octave or not os.path.exists(os.path.join(mex_dir, "stiffpath.mex")):
        pytest.skip("the MATLAB/Octave gateway is not built here (STIFFPATH_MEX_DIR)")
    out = tmp_path / "octave.csv"
    script = (f"addpath('{mex_dir}'); J = stiffpath('run', '{JOB}', '{ROBOT}', struct({options})); "
              "M = [J.t_s J.q_rad J.qd_rad_s J.qdd_rad_s2 double(J.laser) J.power J.line]; "
              f"f = fopen('{out}', 'w'); fprintf(f, '%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\\n', M'); "
              "fclose(f);")
    subprocess.run([octave, "--no-gui", "--no-window-system", "--norc", "--quiet", "--eval", script], check=True)
    return np.loadtxt(out, delimiter=",")


@pytest.mark.parametrize("mode", [None, "thesis", "plain"])
def test_every_surface_gives_the_same_commands(cli, tmp_path, mode):
    flags = {None: [], "thesis": ["--thesis"], "plain": ["--no-compensation"]}[mode]
    python_options = {None: {}, "thesis": {"thesis": True}, "plain": {"compensate": False}}[mode]
    octave_options = {None: "", "thesis": "'thesis', true", "plain": "'compensate', false"}[mode]
    reference = from_cli(cli, tmp_path, *flags)
    assert reference.shape[0] > 100
    python, summary = from_python(**python_options)
    surfaces = {"python": python, "c": from_c(tmp_path, mode)}
    try:
        surfaces["octave"] = from_octave(tmp_path, octave_options)
    except pytest.skip.Exception:
        pass
    for name, commands in surfaces.items():
        assert commands.shape == reference.shape, name
        # Bit for bit: the same JobSpec, the same arithmetic; the C and Octave files print 17 significant digits.
        np.testing.assert_array_equal(commands, reference, err_msg=name)
    # The summary says what was applied, the same way everywhere.
    assert summary["filters"] == ("none" if mode else "two moving averages of 4 ms (8 ms smoothing)")
    assert summary["compensation"] == (mode != "plain")


def test_without_compensation_is_the_planned_path_as_it_is(tmp_path):
    # One meaning everywhere: p_cmd = p and no reference filter unless named, so the commands' targets are the plan's.
    joints, summary = stiffpath.run(file=JOB, robot=ROBOT, compensate=False)
    plan = stiffpath.plan(file=JOB, home_m=None)
    assert summary["smooth_s"] == 0.0 and summary["filters"] == "none"
    assert len(joints) == len(plan)
    np.testing.assert_array_equal(joints["target_m"], plan["p_m"])
    np.testing.assert_array_equal(joints["command_m"], plan["p_m"])


def test_every_joint_file_field_is_in_the_dtypes(cli, tmp_path):
    """stiffpath.joint_file_dtype (made from the field table) decodes the CLI's binary file as the layout above does, and
    every field of stiffpath.joint_file_fields is in joints_dtype under its name, with the CLI's value."""
    out = tmp_path / "cli.bin"
    cli("run", JOB, "--robot", ROBOT, "--format", "bin", "-o", out)
    independent = np.fromfile(out, dtype=RECORD, offset=128)
    records = np.fromfile(out, dtype=stiffpath.joint_file_dtype, offset=128)
    assert stiffpath.joint_file_dtype.itemsize == RECORD.itemsize == 120
    by_layout = {"t_s": independent["t_s"], "power": independent["power"], "line": independent["line"],
                 "laser": independent["laser"]}
    for pair, names in (("q", ("theta1_rad", "theta2_rad")), ("qd", ("omega1_rad_s", "omega2_rad_s")),
                        ("qdd", ("alpha1_rad_s2", "alpha2_rad_s2")), ("p", ("x_m", "y_m")),
                        ("p_cmd", ("xcmd_m", "ycmd_m")), ("F", ("fx_n", "fy_n"))):
        for k, name in enumerate(names):
            by_layout[name] = independent[pair][:, k]
    assert set(records.dtype.names) == set(by_layout)
    for name, column in by_layout.items():
        np.testing.assert_array_equal(records[name], column, err_msg=name)
    assert records["laser"].sum() > 0 and np.ptp(records["power"]) > 0  # laser and power were exercised
    joints, _ = stiffpath.run(file=JOB, robot=ROBOT)
    assert len(joints) == len(records)
    names = [field[0] for field in stiffpath.joint_file_fields]
    csv = tmp_path / "cli.csv"
    cli("run", JOB, "--robot", ROBOT, "-o", csv)
    assert csv.read_text().splitlines()[1] == ",".join(names)
    for csv_name, file_name, member, component, csv_per_si in stiffpath.joint_file_fields:
        column = joints[member] if joints[member].ndim == 1 else joints[member][:, component]
        np.testing.assert_array_equal(column, records[file_name], err_msg=f"joints_dtype's {member} for {csv_name}")
