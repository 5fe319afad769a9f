# The y-line example end to end (matplotlib's Agg backend): it runs, writes a PNG, and its numbers show what the
# thesis's fig. 4.7a shows: compensation reduces the mark's deviation from its line.
import os
import re
import subprocess
import sys

import pytest

from conftest import EXAMPLES


def test_y_line_example_plots_and_compensation_helps(tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "y_line.png"
    done = subprocess.run([sys.executable, str(EXAMPLES / "python" / "y_line.py"), str(out)], check=True,
                          capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    with open(out, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"
    deviation = {m.group(1).strip(): float(m.group(2))
                 for m in re.finditer(r"^(.{24}) length .* max deviation ([0-9.]+) um", done.stdout, re.M)}
    assert set(deviation) == {"without compensation", "quasi-static (thesis)", "dynamic (run's default)"}
    assert deviation["quasi-static (thesis)"] < deviation["without compensation"]
    assert deviation["dynamic (run's default)"] < deviation["without compensation"]
