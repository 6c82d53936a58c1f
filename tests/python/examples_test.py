"""examples/python/figure8.py in a reduced form (two compensated delays, 2 s each): it runs the
Figure 8 study through rpsd.run, reads it with rpsd.load and draws panel (c) into a PNG."""
import os
import subprocess
import sys

import rpsd
from conftest import SRC


def test_figure8_example_draws_panel_c(scratch):
    png = scratch / "figure8c.png"
    done = subprocess.run([sys.executable, str(SRC / "examples/python/figure8.py"), "--out", str(scratch / "f8"),
                           "--delays", "60,90", "--duration", "2", "--png", str(png)],
                          capture_output=True, text=True, timeout=600, env={**os.environ, "MPLBACKEND": "Agg"})
    assert done.returncode == 0, done.stderr
    assert "2 cases" in done.stdout
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10000
    study = rpsd.load(scratch / "f8")
    assert isinstance(study, rpsd.Study) and study.kind == "rpsd_delay_compensation"
    residual = study.tables["damping"]["residual_delay_ms"]
    # 60 ms under-compensates the rig's 69 ms (a positive residual), 90 ms over-compensates.
    assert len(residual) == 2 and residual[0] > 0 > residual[1]
    assert study.tables["damping"]["identified_damping_ratio"][0] < 0 < study.tables["damping"]["identified_damping_ratio"][1]
