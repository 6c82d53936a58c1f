"""results.h5 as a user meets it (docs/results-format.md): written by `rpsd run --format both`,
read with h5py and listed with h5dump; and the file a run killed with SIGKILL leaves.

Run by ctest with Debian's python3 (python3-pytest, python3-h5py); the environment names the
rpsd binary (RPSD_BIN), the source tree (RPSD_SOURCE_DIR) and a scratch folder (RPSD_OUT).
"""
import csv
import os
import re
import shutil
import signal
import subprocess
import time
from pathlib import Path

import h5py
import numpy as np
import pytest

RPSD = os.environ["RPSD_BIN"]
SRC = Path(os.environ["RPSD_SOURCE_DIR"])
OUT = Path(os.environ["RPSD_OUT"])
SCENARIO = SRC / "examples/scenarios/elcentro-sdof.yaml"
SETUP_SCENARIO = SRC / "examples/scenarios/two-actuator-column.yaml"

# Every documented dataset of a run's group, with its unit (docs/results-format.md).
COORDINATOR = {"step": "1", "ground_acceleration_m_per_s2": "m/s^2", "input_energy_j": "J",
               "kinetic_energy_j": "J", "damping_energy_j": "J", "restoring_energy_j": "J",
               "node_status": "1", "limit_flags": "1", "cycle_lateness_s": "s", "feedback_age_periods": "1"}
CHANNEL = {"target_m": "m", "command_m": "m", "measured_m": "m", "measured_force_n": "N",
           "specimen_restoring_force_n": "N", "tracking_indicator_m2": "m^2", "round_trip_s": "s"}
DOF = {"displacement_m": "m", "velocity_m_per_s": "m/s", "acceleration_m_per_s2": "m/s^2",
       "restoring_force_n": "N"}


def run(folder, scenario, *extra):
    shutil.rmtree(folder, ignore_errors=True)
    done = subprocess.run([RPSD, "run", str(scenario), "--out", str(folder), *extra],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return folder


@pytest.fixture(scope="module")
def both():
    return run(OUT / "h5-both", SCENARIO, "--format", "both")


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return {name: [row[i] for row in body] for i, name in enumerate(header)}


def g10(value):
    return "%.10g" % value


def dataset_of(column):
    """The dataset path (below the run's group) of a CSV column."""
    if column in ("time_s",):
        return None
    m = re.fullmatch(r"(.+)_ch(\d+)", column)
    if m:
        group = "held_ch" + m[2] if m[1].startswith("held_") else "ch" + m[2]
        return "experimental_substructure/%s/%s" % (group, m[1])
    m = re.fullmatch(r"(.+)_dof(\d+)", column)
    if m:
        return "simulation_substructure/dof%s/%s" % (m[2], m[1])
    return "coordinator/" + column


def check_equals_csv(h5, run_group, table):
    columns = read_csv(table)
    group = h5[run_group]
    period = group.attrs["period_s"]
    steps = group["coordinator/step"][:]
    assert [str(s) for s in steps] == columns["step"]
    # Time is the step times the period: the CSV's time_s to its 10 digits.
    assert [g10(s * period) for s in steps] == columns["time_s"]
    for column, text in columns.items():
        path = dataset_of(column)
        if path is None:
            continue
        values = group[path][:]
        assert len(values) == len(text), column
        if values.dtype.kind in "iu":
            assert [str(v) for v in values] == text, column
        else:
            assert [g10(v) for v in values] == text, column


def test_layout_and_units(both):
    with h5py.File(both / "results.h5", "r") as f:
        assert {"global_model", "test", "reference", "analysis"} <= set(f)
        for run_group in ("test", "reference"):
            g = f[run_group]
            assert g.attrs["period_s"] == 1.0 / 1024.0 or g.attrs["period_s"] > 0
            assert g.attrs["control_rate_hz"] * g.attrs["period_s"] == pytest.approx(1.0)
            for name, unit in COORDINATOR.items():
                assert g["coordinator"][name].attrs["units"] == unit, name
            for name, unit in CHANNEL.items():
                assert g["experimental_substructure/ch0"][name].attrs["units"] == unit, name
            for name, unit in DOF.items():
                assert g["simulation_substructure/dof0"][name].attrs["units"] == unit, name
            assert g["coordinator/step"].dtype == np.int64
            assert g["coordinator/step"].chunks is not None
            assert g["coordinator/step"].compression == "gzip"
        model = f["global_model"]
        assert model["effective_scenario"][()].decode() == (both / "effective-scenario.yaml").read_text()
        import hashlib, json
        summary = json.loads((both / "summary.json").read_text())
        inputs = summary["provenance"]["inputs"]
        files = model["input_files"]
        assert len(files) == len(inputs)
        for k, entry in enumerate(inputs):
            data = files["file%d" % k]
            assert data.attrs["path"] == entry["file"]
            assert data.attrs["sha256"] == entry["sha256"]
            assert hashlib.sha256(data[:].tobytes()).hexdigest() == entry["sha256"]
        assert summary["results_h5"] == "results.h5"
        analysis = f["analysis"]
        assert json.loads(analysis["summary_json"][()].decode()) == summary
        for name, value in summary["benchmark_criteria"].items():
            stored = analysis["benchmark_criteria"][name][()]
            assert (np.isnan(stored) if value is None else stored == value), name
        assert analysis["channels/ch0/J2_rms_tracking_error_percent"].attrs["units"] == "%"


def test_arrays_equal_the_csv_to_its_digits(both):
    with h5py.File(both / "results.h5", "r") as f:
        check_equals_csv(f, "test", both / "time_history.csv")
        check_equals_csv(f, "reference", both / "reference_history.csv")


def test_setup_dof_view_equals_the_csv():
    folder = run(OUT / "h5-setup", SETUP_SCENARIO, "--format", "both")
    with h5py.File(folder / "results.h5", "r") as f:
        assert "dof_target_m" in f["test/experimental_substructure/ch0"] or \
            "dof_target_rad" in f["test/experimental_substructure/ch0"]
        check_equals_csv(f, "test", folder / "time_history.csv")


def test_held_forces_in_the_test_only_as_the_csv_has_them():
    # The perfect-actuator reference holds no force: its group has no held_chC, as its CSV.
    folder = run(OUT / "h5-held", SRC / "examples/scenarios/column-axial-load.yaml", "--format", "both")
    with h5py.File(folder / "results.h5", "r") as f:
        assert any(name.startswith("held_ch") for name in f["test/experimental_substructure"])
        assert not any(name.startswith("held_ch") for name in f["reference/experimental_substructure"])
        check_equals_csv(f, "test", folder / "time_history.csv")
        check_equals_csv(f, "reference", folder / "reference_history.csv")


def test_h5dump_lists_the_documented_groups(both):
    listing = subprocess.run(["h5dump", "-H", str(both / "results.h5")], capture_output=True, text=True,
                             check=True).stdout
    for group in ("global_model", "input_files", "test", "reference", "coordinator",
                  "experimental_substructure", "ch0", "simulation_substructure", "dof0", "analysis",
                  "benchmark_criteria"):
        assert re.search(r'GROUP "%s"' % group, listing), group
    assert 'ATTRIBUTE "units"' in listing and 'ATTRIBUTE "period_s"' in listing


def test_hdf5_alone_writes_no_csv_and_a_summary():
    folder = run(OUT / "h5-only", SCENARIO, "--format", "hdf5")
    assert not (folder / "time_history.csv").exists()
    assert not (folder / "reference_history.csv").exists()
    assert (folder / "summary.json").exists()
    with h5py.File(folder / "results.h5", "r") as f:
        assert len(f["test/coordinator/step"]) > 0


def test_a_file_that_cannot_grow_stops_the_run_with_exit_5():
    # As a CSV that cannot grow (cli.results.file_size_limit_exit_5): the test stops, it does
    # not run on unrecorded.
    folder = OUT / "h5-file-size-limit"
    shutil.rmtree(folder, ignore_errors=True)
    done = subprocess.run(["prlimit", "--fsize=400000", RPSD, "run", str(SRC / "examples/scenarios/synthetic-sdof.yaml"),
                           "--out", str(folder), "--format", "hdf5", "--set", "ground_motion.synthetic.duration_s=600"],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 5, done.stdout + done.stderr
    import json
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["result"] == "results_not_written"
    assert summary["steps"] < summary["steps_planned"]
    assert "results.h5" in summary["outcome"]
    assert "HDF5-DIAG" not in done.stderr


def test_a_killed_run_leaves_a_prefix_h5py_opens():
    folder = OUT / "h5-killed"
    shutil.rmtree(folder, ignore_errors=True)
    # Long enough to be killed mid-way: 2,000,000 steps as fast as possible.
    process = subprocess.Popen([RPSD, "run", str(SRC / "tests/coordinator/data/sdof-free-vibration.yaml"),
                                "--out", str(folder), "--format", "hdf5", "--set", "free_vibration.duration_s=2000",
                                "--set", "output.record_dofs=[0]"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    path = folder / "results.h5"
    seen = 0
    deadline = time.monotonic() + 120  # a hang guard only
    try:
        # Read it while it is written (SWMR) until a few flushes are in.
        while seen < 20000 and time.monotonic() < deadline and process.poll() is None:
            time.sleep(0.2)
            if not path.exists():
                continue
            try:
                with h5py.File(path, "r", libver="latest", swmr=True) as f:
                    seen = len(f["test/coordinator/step"])
            except (OSError, KeyError):  # not yet in SWMR mode, or not yet flushed
                continue
        assert process.poll() is None, "the run ended before it could be killed"
        assert seen >= 20000
        process.send_signal(signal.SIGKILL)
        process.wait()
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
    # As docs/results-format.md says: clear the superblock's mark, then open it as any file.
    subprocess.run(["h5clear", "-s", str(path)], check=True)
    with h5py.File(path, "r") as f:
        steps = f["test/coordinator/step"][:]
        assert len(steps) >= seen
        assert len(steps) < 2000 * 1024
        assert np.array_equal(steps, np.arange(1, len(steps) + 1))
        for name in CHANNEL:
            assert len(f["test/experimental_substructure/ch0"][name]) == len(steps)
        assert "analysis" not in f
