# Shared helpers of the Python tests: the CLI of the same build (its numbers are the reference) and the source tree.
import json
import os
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("STIFFPATH_SOURCE_DIR", Path(__file__).resolve().parents[3]))
EXAMPLES = SOURCE_DIR / "examples"


@pytest.fixture(scope="session")
def cli():
    """Runs the stiffpath CLI of this build; with --json, returns the parsed document."""
    program = os.environ.get("STIFFPATH_CLI")
    if not program:
        pytest.skip("STIFFPATH_CLI not set (run through ctest)")

    def run(*args):
        out = subprocess.run([program, *map(str, args)], check=True, capture_output=True, text=True).stdout
        return json.loads(out) if "--json" in args else out

    return run
