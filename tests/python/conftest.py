"""The Python module rpsd as a user meets it (docs/python.md), with Debian's python3, pytest,
NumPy and h5py. ctest names the built package (PYTHONPATH=build/python), the rpsd binary
(RPSD_BIN), the source tree (RPSD_SOURCE_DIR) and a scratch folder (RPSD_OUT)."""
import os
import shutil
import subprocess
from pathlib import Path

import pytest

RPSD = os.environ["RPSD_BIN"]
SRC = Path(os.environ["RPSD_SOURCE_DIR"])
SCENARIOS = SRC / "examples/scenarios"
# The paper's SDOF under El Centro, cut to its first 2 s (2048 steps): a run takes well under a second.
SCENARIO = SCENARIOS / "elcentro-sdof.yaml"
SHORT = {"ground_motion.trim.end_s": 2}
SHORT_SET = ["--set", "ground_motion.trim.end_s=2"]


@pytest.fixture
def scratch(request):
    """A fresh folder for one test, under RPSD_OUT."""
    folder = Path(os.environ["RPSD_OUT"]) / request.node.name
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    return folder


def cli(*args, expect=0):
    """Runs the rpsd binary; returns its stdout."""
    done = subprocess.run([RPSD, *map(str, args)], capture_output=True, text=True, timeout=600)
    assert done.returncode == expect, done.stderr
    return done.stdout
