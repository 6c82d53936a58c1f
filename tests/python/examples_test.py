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


def my_controller(out, lead_scale):
    done = subprocess.run([sys.executable, str(SRC / "examples/python/my_controller.py"), "--out", str(out),
                           "--runs", "2", "--duration", "8", "--lead-scale", str(lead_scale)],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    rows = [line.split() for line in done.stdout.splitlines() if line.startswith("J")]
    assert len(rows) == 9
    return {name: (float(a), float(b)) for name, a, b in rows}


def test_my_controller_example_puts_a_python_controller_through_the_benchmark_study(scratch):
    # The example's controller with the released coefficients is G_T: the same criteria as the
    # sample controller's YAML, to the table's digits.
    same = my_controller(scratch / "gt", 1.0)
    for name, (sample, participant) in same.items():
        assert abs(sample - participant) <= 1e-4 * max(1.0, abs(sample)), name
    # A stronger lead tracks with less delay and a smaller error than the sample controller.
    stronger = my_controller(scratch / "lead", 1.1)
    assert stronger["J1_tracking_delay_ms"][1] < stronger["J1_tracking_delay_ms"][0]
    assert stronger["J2_rms_tracking_error_percent"][1] < stronger["J2_rms_tracking_error_percent"][0]
    participant = rpsd.load(scratch / "lead" / "participant")
    assert participant.summary["runs_planned"] == 2
