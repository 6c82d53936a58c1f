"""rpsd.load reads every folder rpsd writes: a test as CSV and as results.h5 (the same arrays to
the CSV's digits), a sweep and a Monte Carlo batch."""
import numpy as np
import pytest

import rpsd
from conftest import SCENARIO, SCENARIOS, SHORT, SHORT_SET, cli


def test_csv_and_hdf5_folders_of_a_run_give_the_same_arrays(scratch):
    csv_run = rpsd.run(SCENARIO, out=scratch / "csv", overrides=SHORT, format="csv")
    h5_run = rpsd.run(SCENARIO, out=scratch / "h5", overrides=SHORT, format="hdf5")
    assert not (scratch / "csv/results.h5").exists() and not (scratch / "h5/time_history.csv").exists()
    from_csv, from_h5 = rpsd.load(scratch / "csv"), rpsd.load(scratch / "h5")
    assert (from_csv.source, from_h5.source) == ("csv", "hdf5")
    assert from_csv.summary == csv_run.summary and from_h5.summary == h5_run.summary
    for a, b in ((from_csv.test, from_h5.test), (from_csv.reference, from_h5.reference)):
        assert sorted(a) == sorted(b)
        assert a.units == b.units
        assert np.array_equal(a.step, b.step) and np.array_equal(a.time_s, b.time_s)
        for name in a:
            assert a[name].dtype == b[name].dtype == np.float64
            assert ["%.10g" % v for v in a[name]] == ["%.10g" % v for v in b[name]], name
    assert from_csv.criteria == from_h5.criteria


def test_both_formats_in_one_folder_load_either_way(scratch):
    rpsd.run(SCENARIO, out=scratch / "both", overrides=SHORT)
    h5, csv = rpsd.load(scratch / "both"), rpsd.load(scratch / "both", source="csv")
    assert (h5.source, csv.source) == ("hdf5", "csv")
    np.testing.assert_allclose(csv.test["measured_m_ch0"], h5.test["measured_m_ch0"], rtol=1e-9, atol=0)


def test_a_sweep_folder_loads(scratch):
    cli("run", SCENARIOS / "elcentro-sdof-compensation-sweep.yaml", "--out", scratch / "sweep",
        "--set", "ground_motion.trim.end_s=0.5")
    sweep = rpsd.load(scratch / "sweep")
    assert isinstance(sweep, rpsd.Sweep) and sweep.result == "completed"
    assert len(sweep.cases) == sweep.table.rows == 8
    assert list(sweep.table["compensation.delay_s"][:2]) == [0.08, 0.09]
    case = sweep.cases[1]
    assert isinstance(case, rpsd.Result) and case.folder.name == sweep.table["folder"][1]
    assert case.test.steps == case.summary["steps"] > 0
    assert case.test.units["measured_m_ch0"] == "m"


def test_a_sweep_written_as_hdf5_loads_each_case_from_its_group_as_from_the_csv(scratch):
    cli("run", SCENARIOS / "elcentro-sdof-compensation-sweep.yaml", "--out", scratch / "both", "--format", "both",
        "--set", "ground_motion.trim.end_s=0.5")
    cli("run", SCENARIOS / "elcentro-sdof-compensation-sweep.yaml", "--out", scratch / "h5", "--format", "hdf5",
        "--set", "ground_motion.trim.end_s=0.5")
    assert not (scratch / "h5/case_001/time_history.csv").exists()
    only_h5 = rpsd.load(scratch / "h5").cases[1]
    from_h5, from_csv = rpsd.load(scratch / "both").cases[1], rpsd.load(scratch / "both", source="csv").cases[1]
    assert (only_h5.source, from_h5.source, from_csv.source) == ("hdf5", "hdf5", "csv")
    assert only_h5.test.steps == only_h5.summary["steps"] > 0
    for name in from_csv.test:
        assert np.array_equal(only_h5.test[name], from_h5.test[name]), name
        assert ["%.10g" % v for v in from_h5.test[name]] == ["%.10g" % v for v in from_csv.test[name]], name
    assert sorted(only_h5.reference) == sorted(from_csv.reference)


def test_a_monte_carlo_folder_loads(scratch):
    cli("run", SCENARIOS / "rths-benchmark-sample-controller-case-1.yaml", "--out", scratch / "mc",
        "--set", "monte_carlo.runs=2", "--set", "ground_motion.trim.end_s=0.5")
    batch = rpsd.load(scratch / "mc")
    assert isinstance(batch, rpsd.MonteCarlo) and batch.summary["runs_planned"] == 2
    assert len(batch.runs) == batch.table.rows == 2
    assert "J2_rms_tracking_error_percent" in batch.table and "mean" in batch.statistics
    run = batch.runs[-1]
    assert run.folder.name == "run_002" and run.summary["steps"] > 0
    # The benchmark's runs keep every k-th step (output.histories: decimated): the history holds
    # exactly the steps k, 2k, ... with their own step indices and times.
    k = run.summary["histories"]["every_steps"]
    assert list(run.test.step) == list(range(k, run.summary["steps"] + 1, k))
    assert run.test.time_s[0] == k * run.test.period_s
    assert {"measured_m_ch0", "displacement_m_dof2"} <= set(run.test)


def test_a_folder_rpsd_did_not_write_is_refused(scratch):
    with pytest.raises(rpsd.ConfigError, match="no summary.json"):
        rpsd.load(scratch)
    with pytest.raises(rpsd.ConfigError, match="no such folder"):
        rpsd.load(scratch / "nothing-here")
