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


# Sweeps and Monte Carlo batches: one results.h5 in the study's folder, a group per case.
SWEEP = SRC / "examples/scenarios/elcentro-sdof-compensation-sweep.yaml"
BENCHMARK = SRC / "examples/scenarios/rths-benchmark-sample-controller-case-1.yaml"
SHORT = ["--set", "ground_motion.trim.end_s=2", "--set", "ground_motion.pad_after_s=0"]


def csv_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def check_table(table, rows, exact=True):
    """A study table dataset holds its CSV's rows: the same fields in order, the same values (to the
    CSV's 17 digits, exact; sweep.csv has a stream's default 6)."""
    assert list(table.dtype.names) == list(rows[0].keys())
    assert len(table) == len(rows)
    assert len(table.attrs["units"]) == len(table.dtype.names)
    for stored, row in zip(table[:], rows):
        for name in table.dtype.names:
            value = stored[name]
            text = row[name]
            if isinstance(value, bytes):
                assert value.decode() == text, name
            elif table.dtype[name].kind in "iu":
                assert str(value) == text, name
            elif text == "":
                assert np.isnan(value), name
            elif exact:
                assert value == float(text), name  # %.17g reads back as the same double
            else:
                assert "%g" % value == text, name


def check_case_group(f, group, folder):
    """A case's group holds what a single test's results.h5 holds."""
    import json
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["results_h5"] == "../results.h5"
    assert summary["results_h5_group"] == "/" + group
    case = f[group]
    assert {"global_model", "test", "reference", "analysis"} <= set(case)
    assert case["global_model/effective_scenario"][()].decode() == (folder / "effective-scenario.yaml").read_text()
    assert json.loads(case["analysis/summary_json"][()].decode()) == summary
    for name, unit in COORDINATOR.items():
        assert case["test/coordinator"][name].attrs["units"] == unit, name
    if (folder / "time_history.csv").exists():
        check_equals_csv(f, group + "/test", folder / "time_history.csv")
        check_equals_csv(f, group + "/reference", folder / "reference_history.csv")


@pytest.fixture(scope="module")
def sweep():
    return run(OUT / "h5-sweep", SWEEP, "--format", "both", *SHORT)


@pytest.fixture(scope="module")
def batch():
    return run(OUT / "h5-batch", BENCHMARK, "--format", "both", "--set", "monte_carlo.runs=3", *SHORT)


def test_a_sweep_writes_one_file_with_a_group_per_case(sweep):
    import json
    summary = json.loads((sweep / "summary.json").read_text())
    assert summary["results_h5"] == "results.h5"
    cases = [c["folder"] for c in summary["cases"]]
    assert len(cases) == 8
    with h5py.File(sweep / "results.h5", "r") as f:
        assert f.attrs["study"] == "rpsd_test_sweep"
        assert set(f) == {"global_model", "analysis", *cases}
        assert f["global_model/effective_scenario"][()].decode() == (sweep / "effective-scenario.yaml").read_text()
        for case in cases:
            assert not (sweep / case / "results.h5").exists()
            check_case_group(f, case, sweep / case)
        check_table(f["analysis/sweep"], csv_rows(sweep / "sweep.csv"), exact=False)
        assert json.loads(f["analysis/summary_json"][()].decode()) == summary
        assert list(f["analysis/sweep"].attrs["units"])[-5:-1] == ["%", "%", "m", "m"]


def test_a_batch_writes_its_runs_and_statistics_tables(batch):
    import json
    summary = json.loads((batch / "summary.json").read_text())
    with h5py.File(batch / "results.h5", "r") as f:
        assert f.attrs["study"] == "rpsd_test_monte_carlo"
        assert set(f) == {"global_model", "analysis", "run_001", "run_002", "run_003"}
        for run_group in ("run_001", "run_002", "run_003"):
            check_case_group(f, run_group, batch / run_group)
            # The benchmark's cases keep every 16th step (256 Hz) by default.
            steps = f[run_group + "/test/coordinator/step"][:]
            assert f[run_group + "/test"].attrs["history_every_steps"] == 16
            assert np.array_equal(steps, np.arange(16, 16 * len(steps) + 1, 16))
        runs = f["analysis/runs"]
        check_table(runs, csv_rows(batch / "runs.csv"))
        units = dict(zip(runs.dtype.names, runs.attrs["units"]))
        assert units["experimental.0.specimen.stiffness_n_per_m"] == "N/m"
        assert units["servo.rths_benchmark_model.a3_per_s"] == "1/s"
        assert units["J2_rms_tracking_error_percent"] == "%"
        statistics = f["analysis/statistics"]
        rows = csv_rows(batch / "statistics.csv")
        assert [q.decode() for q in statistics["quantity"]] == [r["quantity"] for r in rows]
        for stored, row in zip(statistics[:], rows):
            for name in ("mean", "standard_deviation", "minimum", "maximum"):
                assert stored[name] == float(row[name]), name
        assert json.loads(f["analysis/summary_json"][()].decode()) == summary


def test_h5dump_lists_a_batch_file(batch):
    listing = subprocess.run(["h5dump", "-H", str(batch / "results.h5")], capture_output=True, text=True,
                             check=True).stdout
    for group in ("global_model", "run_001", "test", "reference", "analysis"):
        assert re.search(r'GROUP "%s"' % group, listing), group
    assert re.search(r'DATASET "runs" \{\s*DATATYPE\s+H5T_COMPOUND', listing)
    assert re.search(r'DATASET "statistics" \{\s*DATATYPE\s+H5T_COMPOUND', listing)
    assert 'ATTRIBUTE "study"' in listing


def test_a_criteria_only_batch_holds_no_histories():
    folder = run(OUT / "h5-batch-criteria", BENCHMARK, "--format", "hdf5", "--histories", "criteria_only",
                 "--set", "monte_carlo.runs=2", *SHORT)
    with h5py.File(folder / "results.h5", "r") as f:
        for run_group in ("run_001", "run_002"):
            assert set(f[run_group]) == {"global_model", "analysis"}
            assert "J2" in f[run_group + "/analysis/benchmark_criteria"]
        check_table(f["analysis/runs"], csv_rows(folder / "runs.csv"))


def test_decimated_datasets_are_the_full_runs_at_the_kept_steps(both):
    folder = run(OUT / "h5-decimated", SCENARIO, "--format", "hdf5", "--histories", "decimated",
                 "--history-rate-hz", "128")
    with h5py.File(folder / "results.h5", "r") as thin, h5py.File(both / "results.h5", "r") as full:
        every = full["test"].attrs["control_rate_hz"] / 128
        assert thin["test"].attrs["history_every_steps"] == every
        for run_group in ("test", "reference"):
            steps = thin[run_group + "/coordinator/step"][:]
            all_steps = full[run_group + "/coordinator/step"][:]
            kept = all_steps % every == 0
            assert np.array_equal(steps, all_steps[kept])
            for path in ("experimental_substructure/ch0/measured_m", "simulation_substructure/dof0/displacement_m",
                         "coordinator/input_energy_j"):
                # Bit for bit: the kept steps' values, nothing filtered.
                assert np.array_equal(thin[run_group][path][:], full[run_group][path][:][kept]), path


def test_a_killed_batch_keeps_its_finished_runs_whole():
    # The file is closed between runs: a batch killed during a run keeps every run before it
    # whole (with its criteria) and the run under way up to its last flush (docs/results-format.md).
    folder = OUT / "h5-batch-killed"
    shutil.rmtree(folder, ignore_errors=True)
    process = subprocess.Popen([RPSD, "run", str(BENCHMARK), "--out", str(folder), "--format", "hdf5",
                                "--set", "monte_carlo.runs=6"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    path = folder / "results.h5"
    seen = 0
    deadline = time.monotonic() + 300  # a hang guard only
    try:
        # Read it while run_002 is written (SWMR) until some of its steps are in.
        while seen == 0 and time.monotonic() < deadline and process.poll() is None:
            time.sleep(0.02)
            try:
                with h5py.File(path, "r", libver="latest", swmr=True) as f:
                    seen = len(f["run_002/test/coordinator/step"])
            except (OSError, KeyError):  # between runs, not yet in SWMR mode, or not yet flushed
                continue
        assert process.poll() is None, "the batch ended before it could be killed"
        process.send_signal(signal.SIGKILL)
        process.wait()
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
    import json
    finished = json.loads((folder / "run_001" / "summary.json").read_text())
    assert finished["result"] == "completed"
    subprocess.run(["h5clear", "-s", str(folder / "results.h5")], check=True)
    with h5py.File(folder / "results.h5", "r") as f:
        assert "analysis" not in f
        assert json.loads(f["run_001/analysis/summary_json"][()].decode()) == finished
        steps = f["run_001/test/coordinator/step"][:]
        assert steps[-1] == finished["steps"] - finished["steps"] % 16
        assert len(steps) == finished["steps"] // 16
        # The run under way: every step up to its last flush.
        assert len(f["run_002/test/coordinator/step"]) >= seen
        assert "analysis" not in f["run_002"]


def test_a_reader_between_runs_does_not_stop_the_batch():
    # h5py opening the file at the instant a run reopens it for writing holds its lock then: the
    # writer tries again rather than stop the batch (exit 5 before it did).
    folder = OUT / "h5-batch-read"
    shutil.rmtree(folder, ignore_errors=True)
    process = subprocess.Popen([RPSD, "run", str(BENCHMARK), "--out", str(folder), "--format", "hdf5",
                                "--set", "monte_carlo.runs=20", "--set", "ground_motion.trim.end_s=1",
                                "--set", "ground_motion.pad_after_s=0"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 600  # a hang guard only
    while process.poll() is None and time.monotonic() < deadline:
        try:
            with h5py.File(folder / "results.h5", "r", libver="latest", swmr=True):
                pass
        except OSError:  # between runs, or not yet in SWMR mode
            pass
    if process.poll() is None:
        process.kill()
    assert process.wait() == 0
    with h5py.File(folder / "results.h5", "r") as f:
        assert len(f["analysis/runs"]) == 20
