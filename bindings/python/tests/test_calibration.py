# The calibration plate and the fit from Python equal the command line's; bad inputs are refused with their reason.
import json

import pytest

import stiffpath


def test_the_plate_is_the_commands_plate(cli, tmp_path):
    plate = stiffpath.calibration_plate("oc-gu", output_dir=str(tmp_path / "py"))
    cli("calibrate", "plate", "--robot", "oc-gu", "-o", tmp_path / "cli")
    # The same files, byte for byte, and the same as the returned texts.
    for name, key in (("plate.gcode", "gcode"), ("plate.json", "plate")):
        assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / name).read_text() == plate[key]
    doc = json.loads(plate["plate"])
    assert len(doc["marks"]) == plate["strokes"] >= 4 * 3 * 2  # 2 x 2 stations, 3 directions, 2 levels at least
    assert len(doc["fiducials"]) == plate["fiducials"] >= 3
    assert "M204" in plate["gcode"]  # every mark at its own acceleration
    # A lower acceleration writes it into the program (mm/s^2).
    slow = stiffpath.calibration_plate("oc-gu", accel_m_s2=9.80665)
    assert "M204 S9806." in slow["gcode"] and "M204 S49033" not in slow["gcode"]


def test_the_fit_names_what_it_cannot_read(tmp_path):
    try:
        import stiffpath.vision as vision
    except ImportError:
        pytest.skip("built without the vision part (OpenCV)")
    stiffpath.calibration_plate("oc-gu", output_dir=str(tmp_path))
    with pytest.raises(stiffpath.Error, match="missing.csv"):
        vision.calibrate_fit(str(tmp_path / "plate.json"), str(tmp_path / "missing.png"),
                             joints=str(tmp_path / "missing.csv"), robot="oc-gu")
    with pytest.raises(stiffpath.Error, match="nothing.json"):
        vision.calibrate_fit(str(tmp_path / "nothing.json"), str(tmp_path / "missing.png"),
                             joints=str(tmp_path / "missing.csv"), robot="oc-gu")
