# stiffpath.vision against the CLI: scans drawn and measured by `stiffpath render-scan` / `stiffpath scan` and by Python.
import json
import math
import os

import numpy as np
import pytest

import stiffpath

# Skipped only in a build without the vision part; ctest says which it is, and then a missing part is a failure.
if os.environ.get("STIFFPATH_PYTHON_VISION") == "0":
    pytest.skip("built without the vision part (OpenCV)", allow_module_level=True)
try:
    vision = stiffpath.vision
except AttributeError:
    if os.environ.get("STIFFPATH_PYTHON_VISION") == "1":
        raise
    pytest.skip("built without the vision part (OpenCV)", allow_module_level=True)

MM = 1e-3
# JSON numbers carry 12 significant digits (evaluation::round_for_json): the same computation agrees to that.
SAME = dict(rel=1e-10, abs=1e-12)


def assert_metrics_match(metrics, doc):
    """A stiffpath.PathMetrics (SI) against the metrics of a `--json` document (mm, mm²)."""
    assert metrics.length_m / MM == pytest.approx(doc["length_mm"], **SAME)
    assert metrics.deviation_area_m2 * 1e6 == pytest.approx(doc["deviation_area_mm2"], **SAME)
    assert metrics.max_deviation_m / MM == pytest.approx(doc["max_deviation_mm"], **SAME)
    assert metrics.straightness_m / MM == pytest.approx(doc["straightness_mm"], **SAME)
    sides = doc.get("sides", [doc])
    assert len(metrics.sides) == len(sides)
    for side, expected in zip(metrics.sides, sides):
        assert side.length_m / MM == pytest.approx(expected["length_mm"], **SAME)
        assert side.deviation_area_m2 * 1e6 == pytest.approx(expected["deviation_area_mm2"], **SAME)
    corners = doc.get("corners", [])
    assert len(metrics.corners) == len(corners)
    for corner, expected in zip(metrics.corners, corners):
        assert corner.position_m / MM == pytest.approx([expected["x_mm"], expected["y_mm"]], **SAME)
        assert math.degrees(corner.angle_rad) == pytest.approx(expected["angle_deg"], **SAME)


def distance_to_polyline(points, polyline):
    """Distance (m) of each point (N, 2) to a polyline (M, 2): the nearest of its segments."""
    a, b = polyline[:-1], polyline[1:]
    ab = b - a
    t = np.einsum("nmk,mk->nm", points[:, None, :] - a[None], ab) / np.einsum("mk,mk->m", ab, ab)
    nearest = a[None] + np.clip(t, 0, 1)[..., None] * ab[None]
    return np.linalg.norm(points[:, None, :] - nearest, axis=2).min(axis=1)


@pytest.fixture(scope="module")
def wiggly_line(cli, tmp_path_factory):
    """A 30 mm line at 2° with a decaying 0.05 mm vibration, drawn by the CLI; its truth and the CLI's measurement."""
    image = tmp_path_factory.mktemp("scan") / "line.png"
    args = ["--length-mm", 30, "--angle-deg", 2, "--wiggle-mm", 0.05, "--wiggle-wavelength-mm", 6, "--seed", 4]
    truth = cli("render-scan", image, *args, "--json", "--quiet")
    measured = cli("scan", image, "--json", "--quiet")
    return image, args, truth, measured


def test_scan_of_a_file_is_the_cli_measurement(wiggly_line):
    image, _, truth, measured = wiggly_line
    result = vision.scan(image)
    assert result.to_dict() == measured
    assert_metrics_match(result.metrics, measured)
    assert result.width_m / MM == pytest.approx(measured["width_mm"], **SAME)
    assert result.shape == "line" and result.dpi == 1200 and result.dpi_source == "PNG pHYs"
    assert result.image_size_px == tuple(measured["image_px"]) == tuple(truth["image_px"])
    assert result.image == str(image) and result.warnings == measured["warnings"]
    # and both are a measurement of the drawn path (docs/vision.md: lengths within a few µm)
    assert abs(result.metrics.length_m / MM - truth["length_mm"]) < 5e-3
    assert result.width_m == pytest.approx(0.2 * MM, abs=2e-6)


def test_render_draws_the_cli_image_and_truth(cli, wiggly_line):
    _, args, truth, measured = wiggly_line
    options = dict(zip(args[::2], args[1::2]))
    rendered = vision.render_scan(length_m=options["--length-mm"] * MM, angle_rad=math.radians(options["--angle-deg"]),
                                  wiggle_m=options["--wiggle-mm"] * MM,
                                  wiggle_wavelength_m=options["--wiggle-wavelength-mm"] * MM, seed=options["--seed"])
    assert rendered.image.dtype == np.uint8 and rendered.image.shape == tuple(truth["image_px"][::-1])
    assert_metrics_match(rendered.truth, truth)
    # Measuring the array gives the CLI's numbers for its file: the same pixels.
    result = vision.scan(rendered.image, dpi=rendered.dpi)
    assert_metrics_match(result.metrics, measured)
    assert result.image == "<array>" and result.dpi_source == "dpi argument"


def test_centre_line_points_lie_on_the_drawn_path():
    rendered = vision.render_scan(length_m=20 * MM, angle_rad=math.radians(-1.5), wiggle_m=0.08 * MM,
                                  wiggle_wavelength_m=5 * MM, noise=0.005, seed=7)
    result = vision.scan(rendered.image, dpi=rendered.dpi)
    points = result.points_m
    assert points.shape[1] == 2 and points.dtype == np.float64
    # about one centre per pixel column of a near-horizontal 20 mm line (944 px at 1200 dpi)
    assert len(points) == len(result.sides[0].centres_m) and 900 < len(points) < 960
    height_px, width_px = rendered.image.shape
    assert points.min() > 0 and points[:, 0].max() < width_px * 0.0254 / 1200 and points[:, 1].max() < height_px * 0.0254 / 1200
    distance = distance_to_polyline(points, rendered.sides_m[0])
    # sub-pixel centres: a pixel is 21.2 µm at 1200 dpi
    assert np.median(distance) < 1e-6 and distance.max() < 5e-6


def test_triangle_and_corners_match_the_cli(cli, tmp_path):
    image = tmp_path / "triangle.png"
    truth = cli("render-scan", image, "--shape", "triangle", "--side-mm", 15, "--angle-deg", 5, "--json", "--quiet")
    measured = cli("scan", image, "--shape", "triangle", "--json", "--quiet")
    result = vision.scan(str(image), shape="triangle")
    assert result.to_dict() == measured
    assert_metrics_match(result.metrics, measured)
    assert result.shape == "triangle" and result.metrics.closed and len(result.metrics.corners) == 3
    for corner in result.metrics.corners:
        assert corner.angle_rad == pytest.approx(math.pi / 3, abs=1e-3) and corner.path_distance_m is None
    assert result.metrics.length_m / MM == pytest.approx(truth["length_mm"], abs=5e-3)
    # options with units: a 2 mm trim and a 0.5 mm cutoff are the CLI's 2 and 0.5 mm
    trimmed = cli("scan", image, "--shape", "triangle", "--corner-trim-mm", 2, "--spline-cutoff-mm", 0.5, "--json", "--quiet")
    result = vision.scan(image, shape="triangle", corner_trim_m=2 * MM, spline_cutoff_m=0.5 * MM)
    assert_metrics_match(result.metrics, trimmed)
    assert result.to_dict() != measured


def test_resolution_override_and_region(cli, wiggly_line):
    image, _, _, _ = wiggly_line
    measured = cli("scan", image, "--dpi", 600, "--json", "--quiet")
    result = vision.scan(image, dpi=600)
    assert result.dpi == 600 and result.dpi_source == "--dpi"
    assert_metrics_match(result.metrics, measured)
    # twice the pixel size: the same mark reads twice as long (to the µm: the 1 mm spline and trim are not scaled)
    assert result.metrics.length_m == pytest.approx(2 * vision.scan(image).metrics.length_m, abs=2e-6)
    width_px, height_px = vision.scan(image).image_size_px
    roi = (0, 0, width_px, height_px)
    region = cli("scan", image, "--roi", ",".join(map(str, roi)) + "px", "--json", "--quiet")
    assert vision.scan(image, roi_px=roi).to_dict() == region


def test_array_and_file_agree_for_16_bit(tmp_path):
    rendered = vision.render_scan(length_m=15 * MM, bit_depth=16, seed=2)
    assert rendered.image.dtype == np.uint16
    path = tmp_path / "line16.png"
    rendered.save(path)
    from_file = vision.scan(path)
    from_array = vision.scan(rendered.image, dpi=1200)
    assert from_file.dpi_source == "PNG pHYs" and from_file.dpi == 1200
    assert from_file.metrics.length_m == from_array.metrics.length_m
    assert np.array_equal(from_file.points_m, from_array.points_m)
    # a non-contiguous view is measured as its copy
    doubled = np.repeat(rendered.image, 2, axis=1)[:, ::2]
    assert not doubled.flags.c_contiguous
    assert vision.scan(doubled, dpi=1200).metrics.length_m == from_array.metrics.length_m


def test_colour_render_and_grey_scan(tmp_path):
    rendered = vision.render_scan(length_m=10 * MM, colour=True)
    assert rendered.image.shape[2] == 3
    path = tmp_path / "colour.png"
    vision.save_image(path, rendered.image, rendered.dpi)
    assert abs(vision.scan(path).metrics.length_m - rendered.truth.length_m) < 5e-6
    with pytest.raises(ValueError, match="convert a colour image to grey"):
        vision.scan(rendered.image, dpi=1200)


def test_plate_matches_the_cli(cli, tmp_path):
    plate = tmp_path / "plate.json"
    plate.write_text(json.dumps({
        "page_mm": [70, 50],
        "marks": [{"shape": "line", "length_mm": 40, "at_mm": [10, 10]},
                  {"shape": "triangle", "side_mm": 20, "at_mm": [30, 45], "wiggle_mm": 0.05}],
        "labels": [{"text": "P1", "at_mm": [5, 47], "height_mm": 3}]}))
    image = tmp_path / "plate.png"
    truth = cli("render-scan", image, "--plate", plate, "--dpi", 600, "--json", "--quiet")
    measured = cli("scan", image, "--all-marks", "--json", "--quiet")
    result = vision.scan_plate(image)
    assert result.to_dict() == measured
    marks = [m for m in result.marks if m.measured]
    assert len(marks) == len(truth["marks"]) == 2 and len(result.labels) >= 1
    for mark, doc in zip(marks, [m for m in measured["marks"] if m["status"] == "measured"]):
        assert_metrics_match(mark.result.metrics, doc)
        assert np.array(mark.box_m) / MM == pytest.approx(doc["box_mm"], **SAME)
    assert {m.result.shape for m in marks} == {"line", "triangle"}


def test_bad_input_raises_with_the_file(tmp_path):
    missing = tmp_path / "missing.png"
    with pytest.raises(stiffpath.Error, match="no such file") as error:
        vision.scan(missing)
    assert isinstance(error.value, ValueError) and error.value.file == str(missing)
    text = tmp_path / "notes.png"
    text.write_text("not an image\n")
    with pytest.raises(stiffpath.Error, match="not a readable image") as error:
        vision.scan(text)
    assert error.value.file == str(text)
    with pytest.raises(stiffpath.Error, match="no resolution: give dpi"):
        vision.scan(np.zeros((50, 50), np.uint8))
    with pytest.raises(stiffpath.Error) as error:
        vision.scan(np.full((200, 300), 230, np.uint8), dpi=1200)  # blank paper: no mark
    assert error.value.file == "<array>"
    line = vision.render_scan(length_m=5 * MM).image
    with pytest.raises(stiffpath.Error, match="shape: expected line, triangle"):
        vision.scan(line, dpi=1200, shape="square")
    with pytest.raises(stiffpath.Error, match="beyond the image"):
        vision.scan(line, dpi=1200, roi_px=(0, 0, line.shape[1] + 1, line.shape[0]))
    with pytest.raises(ValueError, match="roi_px"):
        vision.scan(line, dpi=1200, roi_px=(0, 0, 0, 10))
    with pytest.raises(stiffpath.Error, match="cutoff"):
        vision.scan(line, dpi=1200, spline_cutoff_m=-1e-3)


def test_wrong_arrays_are_refused():
    with pytest.raises(TypeError, match="uint8 or uint16.*float64"):
        vision.scan(np.zeros((50, 50)), dpi=1200)
    with pytest.raises(TypeError, match="got list"):
        vision.scan([[0, 1], [1, 0]], dpi=1200)
    with pytest.raises(ValueError, match=r"shape \(50,\)"):
        vision.scan(np.zeros(50, np.uint8), dpi=1200)
    with pytest.raises(ValueError, match=r"shape \(5, 5, 4\)"):
        vision.save_image("x.png", np.zeros((5, 5, 4), np.uint8), 1200)


def test_render_refuses_bad_options(tmp_path):
    with pytest.raises(stiffpath.Error, match="dpi"):
        vision.render_scan(dpi=-5)
    with pytest.raises(stiffpath.Error, match="200 Mpx"):
        vision.render_scan(shape="polyline", vertices_m=[[0, 0], [1.5, 1.5]])
    with pytest.raises(ValueError, match="length_m"):
        vision.render_scan(length_m=1e3)
    with pytest.raises(ValueError, match="vertices_m"):
        vision.render_scan(shape="polyline")
    with pytest.raises(ValueError, match="shape"):
        vision.render_scan(shape="circle")
    rendered = vision.render_scan(length_m=2 * MM)
    with pytest.raises(stiffpath.Error):
        rendered.save(tmp_path / "line.bmp")
    assert not (tmp_path / "line.bmp").exists()


def test_threads_measure_alike():
    # scan() releases the GIL: scans in threads run at once and give the serial numbers
    from concurrent.futures import ThreadPoolExecutor
    images = [vision.render_scan(length_m=8 * MM, seed=seed).image for seed in (1, 2)]
    serial = [vision.scan(image, dpi=1200).metrics.length_m for image in images]
    with ThreadPoolExecutor(2) as pool:
        threaded = list(pool.map(lambda image: vision.scan(image, dpi=1200).metrics.length_m, images * 2))
    assert threaded == serial * 2
