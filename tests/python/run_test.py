"""rpsd.run against `rpsd run`: the same scenario gives the CLI's results.h5 bit for bit and its
CSV to its 10 significant digits; a dict scenario gives what its file gives."""
import csv

import h5py
import numpy as np
import yaml

import rpsd
from conftest import SCENARIO, SCENARIOS, SHORT, SHORT_SET, cli


def column_of(group, name):
    """The CSV column of a dataset below /test or /reference (docs/results-format.md)."""
    parts = group.split("/")
    if parts[0] == "coordinator":
        return name
    return "%s_%s" % (name, parts[1].replace("held_", ""))


def h5_columns(run_group):
    found = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
            group, _, dataset = name.rpartition("/")
            found[column_of(group, dataset)] = (obj[:], obj.attrs["units"])

    run_group.visititems(visit)
    return found


def same_bits(a, b):
    a = np.ascontiguousarray(a, dtype=np.float64)
    b = np.ascontiguousarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))


def test_arrays_equal_the_cli_results_h5_bit_for_bit(scratch):
    cli("run", SCENARIO, "--out", scratch / "cli", "--format", "hdf5", *SHORT_SET)
    r = rpsd.run(SCENARIO, out=scratch / "py", overrides=SHORT)
    assert r.source == "hdf5" and (scratch / "py/results.h5").exists()
    with h5py.File(scratch / "cli/results.h5", "r") as f:
        for group, history in (("test", r.test), ("reference", r.reference)):
            datasets = h5_columns(f[group])
            step, _ = datasets.pop("step")
            assert np.array_equal(history.step, step)
            assert history.period_s == f[group].attrs["period_s"]
            assert same_bits(history.time_s, step * f[group].attrs["period_s"])
            assert sorted(history) == sorted(datasets)
            for name, (values, units) in datasets.items():
                assert history[name].dtype == np.float64
                assert same_bits(history[name], values), name
                assert history.units[name] == (units.decode() if isinstance(units, bytes) else units), name
    assert r.summary["result"] == "completed" and r.summary["steps"] == len(r.test.step) == 2048
    assert r.criteria["channels"] == r.summary["channels"]


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return {name: [row[i] for row in rows[1:]] for i, name in enumerate(rows[0])}


def test_arrays_equal_the_cli_csv_to_its_10_digits(scratch):
    cli("run", SCENARIO, "--out", scratch / "cli", "--format", "csv", *SHORT_SET)
    r = rpsd.run(SCENARIO, out=scratch / "py", overrides=SHORT, format="hdf5")
    for table, history in (("time_history.csv", r.test), ("reference_history.csv", r.reference)):
        columns = read_csv(scratch / "cli" / table)
        assert columns.pop("step") == [str(s) for s in history.step]
        assert columns.pop("time_s") == ["%.10g" % t for t in history.time_s]
        assert sorted(columns) == sorted(history)
        for name, texts in columns.items():
            assert ["%.10g" % v for v in history[name]] == texts, name


def test_a_dict_scenario_gives_the_arrays_of_its_file(scratch):
    scenario = yaml.safe_load(SCENARIO.read_text())
    # File names in a dict are relative to the output folder: give them absolute.
    scenario["servo"]["parameters"] = str((SCENARIOS / scenario["servo"]["parameters"]).resolve())
    scenario["ground_motion"]["file"] = str((SCENARIOS / scenario["ground_motion"]["file"]).resolve())
    from_dict = rpsd.run(scenario, out=scratch / "dict", overrides=SHORT)
    from_file = rpsd.run(SCENARIO, out=scratch / "file", overrides=SHORT)
    assert (scratch / "dict/scenario.yaml").exists()
    for a, b in ((from_dict.test, from_file.test), (from_dict.reference, from_file.reference)):
        assert sorted(a) == sorted(b) and np.array_equal(a.step, b.step)
        for name in a:
            assert same_bits(a[name], b[name]), name


def test_without_out_the_results_stay_in_memory_and_the_folder_goes():
    r = rpsd.run(SCENARIO, overrides=SHORT)
    assert not r.folder.exists()
    assert r.test["measured_m_ch0"].shape == (2048,) and np.all(np.isfinite(r.test["measured_m_ch0"]))
    assert r.test.units["measured_force_n_ch0"] == "N"
