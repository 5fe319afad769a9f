#!/usr/bin/env python3
# Purpose: documents how data/thesis/*.csv were transcribed from the OCR'd thesis (tables 2.1-3.9);
# re-run it to regenerate them and to list every garbled cell (left empty, never guessed).
"""Usage: scripts/transcribe_thesis.py SEED.txt OUTDIR  (prints the garbled cells to stdout)."""
import csv
import re
import sys

KGF = [5.0, 9.92, 14.89, 19.83, 24.86]  # table 2.1, steps 1..5
KGF0 = 0.11                              # table 2.1, step 0
G0 = 9.80665
X_MM = [172.132, 222.132, 272.132]
Y_MM = [-75.0, -37.5, 0.0, 37.5, 75.0]
STEP_LABEL = re.compile(r"^(50|100|150|200|250)\s*N$")
VALUE3 = re.compile(r"^-?\d\.\d{3}$")  # tables 2.2-3.9 print every value with 3 decimals


def clean(cell):
    cell = cell.strip()
    m = re.fullmatch(r"\$(.*)\$", cell)
    if m:
        cell = m.group(1).strip()
    return re.sub(r"\\mathbf\{([^}]*)\}", r"\1", cell).replace(" ", "") if "mathbf" in cell else cell


def table_rows(lines, title):
    """Data rows (label, cells) of the table whose caption starts with `title`, in order."""
    start = next(i for i, l in enumerate(lines) if l.startswith(title))
    rows, seen_table = [], False
    for line in lines[start + 1:]:
        if not line.startswith("|"):
            if seen_table:
                break
            continue
        seen_table = True
        cells = [c for c in line.strip().strip("|").split("|")]
        if set("".join(cells).strip()) <= set(":- "):
            continue  # alignment row
        label = clean(cells[0])
        if "gathered" in line or "x}_{" in line.replace(" ", "") or "mathbf{x}" in line or "Delta" in line \
                or "Angular" in line:
            continue  # column or point header
        rows.append((label, [clean(c) for c in cells[1:]]))
    if len(rows) != 15:
        raise SystemExit(f"{title}: expected 15 data rows, got {len(rows)}")
    return rows


def parse(raw, where, garbled):
    if VALUE3.match(raw):
        return raw
    garbled.append((*where, raw))
    return ""


def main(seed, outdir):
    lines = open(seed, encoding="utf-8").read().split("\n")
    garbled, labels = [], []
    cells = {}  # (mech, dir, point, step) -> dict
    disp = [("OC", "+x", "Table 2.2."), ("OC", "-y", "Table 2.3."),
            ("SC", "+x", "Table 3.8."), ("SC", "-y", "Table 3.9.")]
    angles = [("OC", "+x", "Table 3.4."), ("OC", "-y", "Table 3.5."),
              ("SC", "+x", "Table 3.6."), ("SC", "-y", "Table 3.7.")]
    for mech, direction, title in disp:
        for r, (label, row) in enumerate(table_rows(lines, title)):
            xi, step = r // 5, r % 5 + 1
            if not STEP_LABEL.match(label.replace("$", "")):
                labels.append((title, xi + 1, step, label))
            if len(row) != 15:
                raise SystemExit(f"{title} block x{xi+1} step {step}: {len(row)} cells")
            for yi in range(5):
                point = f"x{xi+1}y{yi+1}"
                d = cells.setdefault((mech, direction, point, step), {})
                for k, name in enumerate(("dx_mm", "dy_mm", "dz_mm")):
                    d[name] = parse(row[3 * yi + k], (title, point, step * 50, name), garbled)
    for mech, direction, title in angles:
        for r, (label, row) in enumerate(table_rows(lines, title)):
            xi, step = r // 5, r % 5 + 1
            if len(row) != 10:
                raise SystemExit(f"{title} block x{xi+1} step {step}: {len(row)} cells")
            for yi in range(5):
                point = f"x{xi+1}y{yi+1}"
                d = cells[(mech, direction, point, step)]
                d["rx_deg"] = parse(row[yi], (title, point, step * 50, "rx_deg"), garbled)
                d["ry_deg"] = parse(row[5 + yi], (title, point, step * 50, "ry_deg"), garbled)

    with open(f"{outdir}/displacements.csv", "w", newline="") as f:
        f.write("# Thesis tables 2.1-2.3 and 3.4-3.9 (OCR of the seed); empty cell = garbled in the seed, "
                "see README.md\n")
        w = csv.writer(f, lineterminator="\n")
        w.writerow("mechanism,direction,point,x_mm,y_mm,step,force_kgf,F_N,F_nominal_N,"
                   "dx_mm,dy_mm,dz_mm,rx_deg,ry_deg".split(","))
        for mech in ("OC", "SC"):
            for direction in ("+x", "-y"):
                for xi in range(3):
                    for yi in range(5):
                        point = f"x{xi+1}y{yi+1}"
                        for step in range(1, 6):
                            d = cells[(mech, direction, point, step)]
                            kgf = KGF[step - 1]
                            w.writerow([mech, direction, point, f"{X_MM[xi]:.3f}", f"{Y_MM[yi]:.1f}", step,
                                        f"{kgf:g}", f"{(kgf - KGF0) * G0:.4f}", 50 * step,
                                        d["dx_mm"], d["dy_mm"], d["dz_mm"], d["rx_deg"], d["ry_deg"]])

    # Table 3.2 (OC repeatability): 3 point blocks (x1, x2, x3) of 3 trials + "Max Diff." row,
    # columns err_x, err_y for y1, y3, y5. Table 3.3 (SC) is unreadable: its rows are written empty.
    start = next(i for i, l in enumerate(lines) if l.startswith("Table 3.2."))
    rep, maxdiff = [], []
    for line in lines[start + 1:]:
        if line.startswith("Table 3.3."):
            break
        cells_ = [c.strip() for c in line.strip().strip("|").split("|")]
        if cells_[0] in ("1", "2", "3"):
            rep.append((int(cells_[0]), cells_[1:]))
        elif cells_[0].startswith("Max"):
            maxdiff.append(cells_[1:])
    if len(rep) != 9 or len(maxdiff) != 3:
        raise SystemExit("table 3.2: unexpected shape")
    with open(f"{outdir}/repeatability.csv", "w", newline="") as f:
        f.write("# Thesis table 3.2 (OC); table 3.3 (SC) is garbled beyond reading in the seed: its cells are "
                "empty, see README.md\n")
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["mechanism", "point", "x_mm", "y_mm", "trial", "err_x_mm", "err_y_mm"])
        for mech in ("OC", "SC"):
            for b in range(3):
                for pi, yi in enumerate((0, 2, 4)):
                    for trial, row in rep[3 * b:3 * b + 3]:
                        ex, ey = (row[2 * pi], row[2 * pi + 1]) if mech == "OC" else ("", "")
                        for v in (ex, ey):
                            if v and not re.fullmatch(r"\d\.\d{1,3}", v):
                                raise SystemExit(f"table 3.2: unexpected cell {v!r}")
                        w.writerow([mech, f"x{b+1}y{yi+1}", f"{X_MM[b]:.3f}", f"{Y_MM[yi]:.1f}", trial, ex, ey])
    print("max diff rows of table 3.2:", maxdiff)
    print("garbled row labels (step taken from the row's position):")
    for t in labels:
        print("  ", t)
    print(f"garbled cells ({len(garbled)}):")
    for t in garbled:
        print("  ", t)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
