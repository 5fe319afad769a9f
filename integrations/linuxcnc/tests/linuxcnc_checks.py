"""What the LinuxCNC tests check in the records of `stiffpath linuxcnc run`: reading them, the laser's edges against the
program's laser-on paths, and the binary joint file read by its documented layout (docs/compensation.md)."""
import csv
import math
import struct

RECORD_COLUMNS = ["t_s", "theta1_rad", "theta2_rad", "laser", "power", "x_mm", "y_mm"]


class Checks:
    def __init__(self):
        self.failures = []

    def __call__(self, condition, message):
        if not condition:
            self.failures.append(message)
            print("FAIL:", message)
        return condition


def read_record(path):
    """The CSV of --record / --compare: one dict of floats per servo period; the header must be the documented one."""
    with open(path) as f:
        reader = csv.reader(f)
        header = next(reader)
        if header != RECORD_COLUMNS:
            raise AssertionError("%s: header %s, expected %s" % (path, header, RECORD_COLUMNS))
        return [dict(zip(header, map(float, row))) for row in reader]


def read_joint_file(path):
    """A version-2 binary joint file: (rate_hz, records), each record (t, θ1, θ2, power, laser, x_m, y_m)."""
    with open(path, "rb") as f:
        data = f.read()
    magic, version, record_bytes, rate_hz, count = struct.unpack_from("<8sIIdQ", data, 0)
    if magic != b"SPJOINT\0" or version != 2 or record_bytes != 120 or len(data) != 128 + count * 120:
        raise AssertionError("%s is not a version-2 stiffpath binary joint file" % path)
    records = []
    for i in range(count):
        v = struct.unpack_from("<14diB", data, 128 + i * 120)
        records.append((v[0], v[1], v[2], v[13], v[15], v[7], v[8]))
    return rate_hz, records


def stretches(rows):
    """The laser-on stretches as (first on period, first off period after it)."""
    out, start = [], None
    for k, r in enumerate(rows):
        if r["laser"] and start is None:
            start = k
        elif not r["laser"] and start is not None:
            out.append((start, k))
            start = None
    if start is not None:
        out.append((start, len(rows)))
    return out


def nearest(rows, point, around, last):
    """Within ±60 periods of `around`: the smallest distance (mm) of the planned point (x_mm, y_mm) to `point`, and
    the last (or first) period at that distance (to 1e-9 mm: a point standing still repeats its numbers exactly)."""
    window = range(max(0, around - 60), min(len(rows), around + 61))
    d = {k: math.hypot(rows[k]["x_mm"] - point[0], rows[k]["y_mm"] - point[1]) for k in window}
    least = min(d.values())
    at = [k for k in window if d[k] <= least + 1e-9]
    return least, (at[-1] if last else at[0])


def check_laser_edges(check, rows, expected, label):
    """expected: one (begin (x, y) mm, end (x, y) mm, power) per laser-on path of the program, in order. The laser must
    switch on within one period of the period after the planned point is nearest to the path's beginning (the last
    such period: it may stand there), off within one period of the period it is nearest to the path's end (the first),
    with the program's power all along, and nowhere else. Where the planned point stands still inside a path (the
    reference filters rest at a corner before moving on) the power may be 0: the program did not ask for the rest."""
    found = stretches(rows)
    check(len(found) == len(expected), "%s: %d laser-on stretches, the program has %d" % (label, len(found), len(expected)))
    worst = 0
    for (on, off), (begin, end, power) in zip(found, expected):
        gap_b, leave = nearest(rows, begin, on, last=True)
        gap_e, arrive = nearest(rows, end, off, last=False)
        check(gap_b <= 0.005 and gap_e <= 0.005, "%s: the planned points pass %s and %s (within %.4f and %.4f mm)"
              % (label, begin, end, gap_b, gap_e))
        check(abs(on - (leave + 1)) <= 1, "%s: the laser comes on in period %d, the planned point leaves %s after period %d"
              % (label, on, begin, leave))
        check(abs(off - arrive) <= 1, "%s: the laser goes off in period %d, the planned point reaches %s in period %d"
              % (label, off, end, arrive))
        worst = max(worst, abs(on - (leave + 1)), abs(off - arrive))
        def standing(k):  # the same point as the period before or after it: a rest begins, goes on or ends here
            return any(math.hypot(rows[j]["x_mm"] - rows[k]["x_mm"], rows[j]["y_mm"] - rows[k]["y_mm"]) <= 1e-6
                       for j in (k - 1, k + 1) if 0 <= j < len(rows))
        check(all(abs(rows[k]["power"] - power) <= 1e-6 or (standing(k) and rows[k]["power"] == 0.0)
                  for k in range(on, off)),
              "%s: the power is %g all along the path from %s (0 only where it stands still)" % (label, power, begin))
    return worst
