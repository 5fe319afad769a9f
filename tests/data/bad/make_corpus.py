#!/usr/bin/env python3
"""Writes the malformed-input corpus (tests/data/bad/<reader>/) and its expect.txt files.

Each case puts one bad value at a known place of an otherwise valid file, so the expected location
(line:column, or the record number of a binary file) and the offending text are known independently
of the tool's output. usage: make_corpus.py STIFFPATH_CLI [GROUP...]   (the CLI writes the valid joint and
model files that some cases start from; GROUPs, default all: tables robots model joints images plates
calibration_plates).
"""
import json
import re
import os
import struct
import subprocess
import sys
import tempfile
import zlib

here = os.path.dirname(os.path.abspath(__file__))


def write(reader, name, data, where, value):
    folder = os.path.join(here, reader)
    os.makedirs(folder, exist_ok=True)
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(folder, name), mode) as f:
        f.write(data)
    expect[reader].append(f"{name}\t{where}\t{value}")


def csv_case(reader, name, header, rows, line, column_name, value, dup=False):
    """rows: list of dicts; the cell (line counted from 1 = header) of column_name becomes value."""
    names = header.split(",")
    if dup:
        names.append(column_name)
    lines = [",".join(names)]
    for r in rows:
        lines.append(",".join(r.get(n, "") for n in names))
    if dup:
        col = len(",".join(names[:-1])) + 2
        write(reader, name, "\n".join(lines) + "\n", f"1:{col}", column_name)
        return
    cells = lines[line - 1].split(",")
    i = names.index(column_name)
    cells[i] = value
    lines[line - 1] = ",".join(cells)
    col = len(",".join(cells[:i])) + (2 if i > 0 else 1)
    write(reader, name, "\n".join(lines) + "\n", f"{line}:{col}", value)


expect = {}


def tables():
    expect["displacement_table"] = []
    h = "mechanism,direction,point,x_mm,y_mm,step,force_kgf,F_N,F_nominal_N,dx_mm,dy_mm"
    rows = [dict(mechanism="OC", direction="+x", point="p1", x_mm="200", y_mm="0", step=str(k), force_kgf=str(5 * k),
                 F_N=f"{49.03 * k:.2f}", F_nominal_N=str(50 * k), dx_mm=f"{0.01 * k:.3f}", dy_mm="0.001")
            for k in (1, 2, 3)]
    t = "displacement_table"
    csv_case(t, "dx_1e300.csv", h, rows, 3, "dx_mm", "1e300")
    csv_case(t, "dy_1e200.csv", h, rows, 2, "dy_mm", "-1e200")
    csv_case(t, "x_1e308.csv", h, rows, 4, "x_mm", "1e308")
    csv_case(t, "force_1e400.csv", h, rows, 2, "F_N", "1e400")
    csv_case(t, "force_nan.csv", h, rows, 3, "F_N", "nan")
    csv_case(t, "dx_200_mm.csv", h, rows, 2, "dx_mm", "200")
    csv_case(t, "duplicate_column.csv", h, rows, 1, "dx_mm", None, dup=True)
    # A point name that is not UTF-8 (fit once ended in exit 1 writing it into the model file).
    plain = [h] + [",".join(r[n] for n in h.split(",")) for r in rows]
    lines = list(plain)
    lines[2] = lines[2].replace(",p1,", ",p\udcff1,")
    text = ("\n".join(lines) + "\n").encode("utf-8", "surrogateescape")
    write(t, "point_not_utf8.csv", text, f"3:{lines[2].index('p') + 1}", "not valid UTF-8")
    # A line longer than a CSV line may be (64 KiB), refused at its line before it is read whole.
    long_line = plain[1].replace(",p1,", ",p" + "1" * 70000 + ",")
    write(t, "line_70_kB.csv", "\n".join([plain[0], long_line] + plain[2:]) + "\n", "2:1", "LIMIT: line longer than 65536")

    expect["campaign"] = []
    h = "point,x_mm,y_mm,direction,step,reading,force_kgf,Ux_mm,Uy_mm,Uz_mm,Lx_mm,Ly_mm,Lz_mm"
    rows = [dict(point="P", x_mm="200", y_mm="0", direction="+x", step=str(k), reading="1", force_kgf=str(0.11 if k == 0 else 5 * k),
                 Ux_mm=f"{200 + 0.16 * k:.3f}", Uy_mm="0.000", Uz_mm="160.000", Lx_mm="200.000", Ly_mm="0.000", Lz_mm="0.000")
            for k in (0, 1, 2)]
    t = "campaign"
    csv_case(t, "ux_1e300.csv", h, rows, 3, "Ux_mm", "1e300")
    csv_case(t, "lz_1e13.csv", h, rows, 4, "Lz_mm", "1e13")
    csv_case(t, "force_inf.csv", h, rows, 2, "force_kgf", "inf")
    csv_case(t, "duplicate_column.csv", h, rows, 1, "Uy_mm", None, dup=True)
    # Readings the reader accepts (within ±1e12) whose displacement no table holds: `measure` refuses to write
    # a table its own reader would refuse, naming the readings' line.
    lines = [h] + [",".join(r[n] for n in h.split(",")) for r in rows]
    lines[2] = lines[2].replace("200.160", "5.7e10", 1)
    write(t, "displacement_5.7e10_mm.csv", "\n".join(lines) + "\n", "3", "beyond the ±100 mm a displacement table holds")

    expect["repeatability"] = []
    h = "mechanism,point,x_mm,y_mm,trial,err_x_mm,err_y_mm"
    rows = [dict(mechanism="OC", point="p1", x_mm="200", y_mm="0", trial=str(k), err_x_mm=f"{0.01 * k:.3f}", err_y_mm="0.002")
            for k in (1, 2, 3)]
    t = "repeatability"
    csv_case(t, "err_1e308.csv", h, rows, 3, "err_x_mm", "1e308")
    csv_case(t, "x_nan.csv", h, rows, 2, "x_mm", "nan")
    csv_case(t, "duplicate_column.csv", h, rows, 1, "err_y_mm", None, dup=True)


def position(text, needle, occurrence=1):
    at = -1
    for _ in range(occurrence):
        at = text.index(needle, at + 1)
    line = text.count("\n", 0, at) + 1
    return f"{line}:{at - (text.rfind(chr(10), 0, at) + 1) + 1}"


def json_cases(reader, base_text, key, bad_number, named=None):
    expect[reader] = []
    # A key given twice: the second one is refused, at its own position.
    lines = base_text.split("\n")
    i = next(k for k, l in enumerate(lines) if l.strip().startswith(f'"{key}"'))
    dup = lines[:i + 1] + [lines[i]] + lines[i + 1:]
    text = "\n".join(dup)
    write(reader, "duplicate_key.json", text, position(text, f'"{key}"', 2), key)
    # A number beyond double range.
    v = lines[i].split(":", 1)[1].strip().rstrip(",")
    text = base_text.replace(lines[i], lines[i].replace(v, "1e400", 1), 1)
    write(reader, "number_1e400.json", text, position(text, "1e400"), "1e400")
    text = base_text.replace(lines[i], lines[i].replace(v, bad_number, 1), 1)
    write(reader, f"{key}_{bad_number.replace('-', 'minus')}.json", text, position(text, f'"{key}"'), named or bad_number)


def depth_position(text, limit=64):
    """line:column of the bracket that makes the nesting one deeper than `limit` (outside strings)."""
    depth, in_string, escaped = 0, False, False
    for at, c in enumerate(text):
        if in_string:
            if escaped:
                escaped = False
            elif c == "\\":
                escaped = True
            elif c == '"':
                in_string = False
        elif c == '"':
            in_string = True
        elif c in "[{":
            depth += 1
            if depth > limit:
                line = text.count("\n", 0, at) + 1
                return f"{line}:{at - (text.rfind(chr(10), 0, at) + 1) + 1}"
        elif c in "]}":
            depth -= 1
    raise ValueError("not that deep")


def robots():
    with open(os.path.join(here, "..", "..", "..", "data", "robots", "oc-gu.json")) as f:
        # Its data by their built-in names, so the copy in tests/data/bad/robot/ finds them.
        base = f.read().replace('"../thesis/', '"builtin:thesis/')
    json_cases("robot", base, "moving_mass_kg", "1e300", "RANGE: 1e+300")
    # 20 000 nested objects in 120 kB (every reader and the C interface once died of it, SIGSEGV).
    n = 20000
    description = base[base.index('"description"'):base.index("\n", base.index('"description"'))].rstrip(",")
    deep = base.replace(description, '"description": ' + '{"a":' * n + "1" + "}" * n, 1)
    write("robot", "nested_20000_objects.json", deep, depth_position(deep), "LIMIT: nested more than 64 levels")
    # Physical ranges: a CG a kilometre above G, a mass of the smallest double.
    text = base.replace('"height_above_G_mm": 35.9', '"height_above_G_mm": 1e6', 1)
    write("robot", "cg_height_1e6_mm.json", text, position(text, '"height_above_G_mm"'), "RANGE: 1000000.0 mm is outside the physical range")
    text = base.replace('"moving_mass_kg": 3.6', '"moving_mass_kg": 5e-324', 1)
    write("robot", "moving_mass_5e-324_kg.json", text, position(text, '"moving_mass_kg"'), "e-324 kg is outside the physical range")
    # One key per meaning: a table and a model file (the model used to win silently).
    text = base.replace('"method": "bilinear"', '"method": "bilinear",\n    "model": "builtin:models/none.json"', 1)
    write("robot", "table_and_model.json", text, position(text, '"model"'), "not both")


def model(cli, tmp):
    path = os.path.join(tmp, "model.json")
    subprocess.run([cli, "fit", "--method", "physical", "-o", path], check=True, stdout=subprocess.DEVNULL)
    with open(path) as f:
        text = f.read()
    json_cases("model", text, "order", "1e300", "RANGE: 1e+300")
    # A coefficient of 1e300: the compliance it gives over the measured region is refused at D_um_per_N.
    first = text.index("[", text.index('"D_um_per_N"') + 15) + 1
    value_at = first + len(text[first:]) - len(text[first:].lstrip())
    end = text.index(",", value_at)
    bad = text[:value_at] + "1e300" + text[end:]
    write("model", "compliance_1e300.json", bad, position(bad, '"D_um_per_N"'), "RANGE: the model's compliance")
    # Every D coefficient negated: a negative definite compliance, which would reverse the correction.
    start = text.index("[", text.index('"D_um_per_N"'))
    end = text.index("]\n", start)
    block = text[start:end]
    negated = re.sub(r"(-?)(\d[\d.eE+-]*)", lambda m: ("" if m.group(1) else "-") + m.group(2), block)
    neg = text[:start] + negated + text[end:]
    write("model", "compliance_negated.json", neg, position(neg, '"D_um_per_N"'), "PHYSICS: the model's compliance")
    # 20 000 nested arrays in 40 kB (1.4 GB of memory for the key scanner, then SIGSEGV).
    n = 20000
    deep = text.replace('"provenance"', '"deep": ' + "[" * n + "]" * n + ',\n  "provenance"', 1)
    write("model", "nested_20000_arrays.json", deep, depth_position(deep), "LIMIT: nested more than 64 levels")


def joints(cli, tmp):
    expect["joints"] = []
    job = os.path.join(tmp, "job.gcode")
    with open(job, "w") as f:
        f.write("G0 X200 Y0\nM3 S500\nG1 X201 F600\nM5\n")
    csv_path, bin_path = os.path.join(tmp, "j.csv"), os.path.join(tmp, "j.bin")
    subprocess.run([cli, "run", job, "-o", csv_path], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([cli, "run", job, "-o", bin_path, "--format", "bin"], check=True, stdout=subprocess.DEVNULL)
    with open(csv_path) as f:  # without the first line's comment (rate, robot): the cases below put their own
        lines = [l for l in f.read().split("\n") if not l.startswith("#")][:8]
    header = lines[0].split(",")

    def cell(name, line, value, newtext=None):
        rows = [l.split(",") for l in lines]
        i = header.index(value[0])
        rows[line - 1][i] = value[1]
        text = "\n".join(",".join(r) for r in rows) + "\n"
        col = len(",".join(rows[line - 1][:i])) + (2 if i > 0 else 1)
        write("joints", name, text, f"{line}:{col}", value[2])

    t3 = float(lines[2].split(",")[0])
    cell("time_gap_200_s.csv", 4, ("t_s", f"{t3 + 200:.6f}", "is 200 s after"))
    cell("time_backwards.csv", 4, ("t_s", "0.000000", "0"))
    cell("theta_1e300.csv", 5, ("theta1_rad", "1e300", "1e300"))
    cell("force_nan.csv", 3, ("fx_n", "nan", "nan"))
    # The first line's rate, refused as the binary header's is.
    for name, rate in (("rate_nan.csv", "nan"), ("rate_zero.csv", "0"), ("rate_1e300.csv", "1e300"), ("rate_fast.csv", "fast")):
        comment = f"# stiffpath joints rate_hz={rate} geometry_sha256=- robot=oc-gu"
        write("joints", name, comment + "\n" + "\n".join(lines) + "\n", f"1:{comment.index('rate_hz=') + 9}", f"rate_hz={rate}")
    dup = [lines[0] + ",t_s"] + [l + ",0" for l in lines[1:] if l]
    write("joints", "duplicate_column.csv", "\n".join(dup) + "\n", f"1:{len(lines[0]) + 2}", "t_s")

    with open(bin_path, "rb") as f:
        data = bytearray(f.read())
    version, rec = struct.unpack_from("<II", data, 8)  # the header says its layout (docs/compensation.md)
    head = 64 if version == 1 else 128

    def record(k):  # 1-based
        return head + (k - 1) * rec

    gap = bytearray(data)
    t = struct.unpack_from("<d", gap, record(3))[0]
    struct.pack_into("<d", gap, record(3), t + 1e6)
    write("joints", "time_gap_1e6_s.bin", bytes(gap), "record 3", "t_s")
    nan = bytearray(data)
    struct.pack_into("<d", nan, record(2) + 8, float("nan"))
    write("joints", "theta_nan.bin", bytes(nan), "record 2", "theta1_rad")
    huge = bytearray(data)
    struct.pack_into("<d", huge, record(4) + 8 * 11, 1e300)
    write("joints", "force_1e300.bin", bytes(huge), "record 4", "1e+300")
    write("joints", "truncated.bin", bytes(data[:record(3) + 50]), "record 3", "truncated")
    rate = bytearray(data)
    struct.pack_into("<d", rate, 16, 0.0)
    write("joints", "rate_zero.bin", bytes(rate), "header", "rate 0 Hz")


def png_chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)


def images():
    expect["image"] = []
    sig = b"\x89PNG\r\n\x1a\n"
    for name, w, h in (("png_1e5_by_1e5.png", 100000, 100000), ("png_width_2e9.png", 2_000_000_000, 1)):
        ihdr = png_chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
        idat = png_chunk(b"IDAT", zlib.compress(b"\x00" * 64))
        write("image", name, sig + ihdr + idat + png_chunk(b"IEND", b""), "-", str(w))
    write("image", "not_an_image.png", b"this is text, not a PNG\n", "-", "not a readable image")
    # A resolution outside the 10..100000 dpi of a scan: refused, naming what the file stores (a 1 px/m PNG
    # was measured as a 237 000 mm line; 0 px/m was reported as "stores no resolution").
    grey = png_chunk(b"IHDR", struct.pack(">IIBBBBB", 4, 4, 8, 0, 0, 0, 0))
    pixels = png_chunk(b"IDAT", zlib.compress(b"\x00\xc8\xc8\xc8\xc8" * 4))
    for name, ppm in (("png_1_px_per_m.png", 1), ("png_0_px_per_m.png", 0), ("png_4e9_px_per_m.png", 4_000_000_000)):
        phys = png_chunk(b"pHYs", struct.pack(">IIB", ppm, ppm, 1))
        write("image", name, sig + grey + phys + pixels + png_chunk(b"IEND", b""), "-", f"{ppm} × {ppm} px/m")


def plates():
    """Plate files (render-scan --plate) and marked paths (render-scan --path-csv): each bad field refused at its
    line and column, exit 2, no image (vertices of 4.3e9 mm and paths of 1e7 mm once ended in bad_alloc, exit 1;
    unknown keys and labels off the page were accepted)."""
    expect["plate"] = []
    base = ('{\n  "page_mm": [100, 80],\n  "marks": [\n'
            '    {"id": "x", "shape": "line", "length_mm": 40, "at_mm": [10, 20]},\n'
            '    {"shape": "polyline", "vertices_mm": [[0, 0], [20, 0], [20, 10]], "at_mm": [50, 40]}\n  ],\n'
            '  "fiducials": [{"at_mm": [8, 70]}],\n'
            '  "labels": [{"text": "X 5G", "at_mm": [10, 16], "height_mm": 3}]\n}\n')
    cases = [
        ("unknown_key.json", base.replace('"page_mm"', '"colour": "red",\n  "page_mm"'), '"colour"', "unknown field"),
        ("unknown_mark_key.json", base.replace('"length_mm": 40', '"length_mm": 40, "lenght_mm": 40'), '"lenght_mm"', "unknown field"),
        ("vertex_4e9_mm.json", base.replace("[20, 0], [20, 10]", "[4.3e9, 0], [20, 10]"), "[4.3e9", "4300000000"),
        ("length_1e300_mm.json", base.replace('"length_mm": 40', '"length_mm": 1e300'), '"length_mm"', "1e+300"),
        ("label_off_the_page.json", base.replace('"at_mm": [10, 16], "height_mm": 3', '"at_mm": [92, 16], "height_mm": 3'),
         '{"text"', "is not on the"),
        ("mark_off_the_page.json", base.replace('"at_mm": [10, 20]', '"at_mm": [70, 20]'), '{"id"', "does not fit on the"),
        ("fiducial_off_the_page.json", base.replace('"at_mm": [8, 70]', '"at_mm": [98, 70]'), '{"at_mm": [98', "does not fit on the"),
        ("cross_reaches_the_ring.json", base.replace('"at_mm": [8, 70]}', '"at_mm": [8, 70], "radius_mm": 3, "cross_arm_mm": 2.9}'),
         '{"at_mm": [8, 70]', "must stop a mark's width short"),
        ("wiggle_of_1_um.json", base.replace('"length_mm": 40, "at_mm": [10, 20]}',
                                            '"length_mm": 80, "at_mm": [10, 20], "wiggle_mm": 0.1, "wiggle_wavelength_mm": 0.001}'),
         '"shape": "line"', "render budget"),
        ("bed_smaller_than_the_mark.json", base.replace('"labels"', '"scanner": {"bed_mm": [40, 40]},\n  "labels"'), '{"id"',
         "lies off the scanner's bed"),
    ]
    for name, text, needle, value in cases:
        write("plate", name, text, position(text, needle), value)
    expect["mark_csv"] = []
    header = "x_mm,y_mm\n"
    for name, rows, line, col, value in [
        ("x_1e7_mm.csv", "0,0\n1e7,0\n10,0\n", 3, 1, "1e7"),
        ("y_minus_3000_mm.csv", "0,0\n5,0\n5,-3000\n", 4, 3, "-3000"),
        ("x_nan.csv", "0,0\nnan,0\n", 3, 1, "nan"),
        ("one_point.csv", "4,4\n4,4\n", None, None, "at least two distinct points"),
    ]:
        write("mark_csv", name, header + rows, f"{line}:{col}" if line else "-", value)


def calibration_plates(cli, tmp):
    """Calibration plates (calibrate plate's plate.json, as calibrate fit reads it): arcs and timing strokes with bad
    fields, refused at their line and column before the scan is opened."""
    expect["calibration_plate"] = []
    subprocess.run([cli, "calibrate", "plate", "--robot", "oc-gu", "-o", os.path.join(tmp, "cal")], check=True,
                   stdout=subprocess.DEVNULL)
    with open(os.path.join(tmp, "cal", "plate.json")) as f:
        doc = json.load(f)
    # The first station's marks only, each arc's polyline its start and end (the reader needs no more): small files.
    station = doc["marks"][0]["id"].split("-")[0] + "-"
    doc["marks"] = [m for m in doc["marks"] if m["id"].startswith(station)]
    for m in doc["marks"]:
        if m["kind"] == "arc":
            m["polyline_mm"] = [m["polyline_mm"][0], m["polyline_mm"][-1]]
    base = json.dumps(doc, indent=2) + "\n"
    kinds = [m["kind"] for m in doc["marks"]]
    first_arc = kinds.index("arc") + 1  # occurrence of an arc's keys among all marks' (only arcs have centre_mm)
    first_timing = kinds.index("timing")
    arc = doc["marks"][first_arc - 1]
    sweep = json.dumps(arc["sweep_deg"])
    timing_run = json.dumps(doc["marks"][first_timing]["run_mm"])
    cases = []
    text = base.replace('"kind": "ringing"', '"kind": "spiral"', 1)
    cases.append(("kind_spiral.json", text, position(text, '"kind": "spiral"'), "spiral"))
    text = base.replace(f'"sweep_deg": {sweep}', '"sweep_deg": 5', 1)
    cases.append(("arc_of_5_deg.json", text, position(text, '"sweep_deg": 5'), "at least 10 deg"))
    moved = json.loads(base)
    moved["marks"][first_arc - 1]["centre_mm"][1] += 0.5  # (along x, start and end would stay equally far)
    text = json.dumps(moved, indent=2) + "\n"
    cases.append(("arc_end_off_its_circle.json", text, position(text, '"polyline_mm"', first_arc),
                  "must lie on its circle"))
    text = base.replace('"kind": "ringing",', '"kind": "ringing",\n      "run_mm": 3,', 1)
    cases.append(("run_on_a_ringing_stroke.json", text, position(text, '"run_mm": 3'), "only a timing stroke"))
    text = base.replace(f'"run_mm": {timing_run}', '"run_mm": -1', 1)
    cases.append(("timing_run_minus_1_mm.json", text, position(text, '"run_mm": -1'), "-1"))
    text = base.replace('"sweep_deg"', '"sweep_degrees"', 1)
    cases.append(("arc_misspelt_key.json", text, position(text, '"sweep_degrees"'), "unknown field"))
    for name, text, where, value in cases:
        write("calibration_plate", name, text, where, value)


def main():
    cli = sys.argv[1]
    only = set(sys.argv[2:])  # groups to write (default: all): tables robots model joints images plates calibration_plates
    wanted = lambda group: not only or group in only
    if wanted("tables"):
        tables()
    if wanted("robots"):
        robots()
    with tempfile.TemporaryDirectory() as tmp:
        if wanted("model"):
            model(cli, tmp)
        if wanted("joints"):
            joints(cli, tmp)
        if wanted("calibration_plates"):
            calibration_plates(cli, tmp)
    if wanted("images"):
        images()
    if wanted("plates"):
        plates()
    for reader, lines in expect.items():
        with open(os.path.join(here, reader, "expect.txt"), "w") as f:
            f.write("# file<TAB>where (line:column, record N, header or - for the file)<TAB>text the message must name\n")
            f.write("\n".join(lines) + "\n")


main()
