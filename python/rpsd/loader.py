"""rpsd.load: any folder rpsd wrote (a test as CSV or results.h5, a sweep, a Monte Carlo batch,
one of the paper's studies) into the objects of rpsd.results."""
import csv
import json
import re
from pathlib import Path

import numpy as np

from .errors import ConfigError
from .results import History, MonteCarlo, Result, Study, Sweep, Table, _Cases

__all__ = ["load"]

# A CSV column's unit from its name's suffix, as rpsd names them (docs/results-format.md gives
# each dataset of results.h5 the same unit in its `units` attribute).
_UNIT_SUFFIXES = [("_m_per_s2", "m/s^2"), ("_m_per_s", "m/s"), ("_n_m", "N*m"), ("_m2", "m^2"),
                  ("_rad", "rad"), ("_m", "m"), ("_n", "N"), ("_j", "J"), ("_s", "s")]
_CHANNEL_OR_DOF = re.compile(r"^(.+)_(ch|dof)\d+$")


def _unit_of(column):
    m = _CHANNEL_OR_DOF.match(column)
    base = m[1] if m else column
    for suffix, unit in _UNIT_SUFFIXES:
        if base.endswith(suffix):
            return unit
    return "1"


def _read_summary(folder):
    try:
        with open(folder / "summary.json") as f:
            return json.load(f)
    except FileNotFoundError:
        raise ConfigError("%s: not a folder rpsd wrote (no summary.json)" % folder) from None


def _history_from_csv(path, period_s):
    with open(path, newline="") as f:
        header = next(csv.reader(f))
    values = np.loadtxt(path, delimiter=",", skiprows=1, dtype=np.float64, ndmin=2)
    if values.shape[0] == 0:
        values = np.zeros((0, len(header)))
    step = values[:, header.index("step")].astype(np.int64)
    columns = {name: np.ascontiguousarray(values[:, i]) for i, name in enumerate(header)
               if name not in ("step", "time_s")}
    return History(step, period_s, columns, {name: _unit_of(name) for name in columns})


def _column_name(group, dataset):
    """The CSV column of a dataset of /test or /reference (docs/results-format.md)."""
    part, _, rest = group.partition("/")
    if part == "coordinator":
        return dataset
    suffix = re.sub(r"^held_", "", rest)  # held_ch1 -> ch1
    return "%s_%s" % (dataset, suffix)


def _history_from_h5(run_group):
    import h5py  # only needed for results.h5

    datasets = []
    run_group.visititems(lambda name, obj: datasets.append((name, obj)) if isinstance(obj, h5py.Dataset) else None)
    # A crashed run's datasets may differ in length by the last extension: keep the steps all hold.
    steps = min(obj.shape[0] for _, obj in datasets)
    columns, units, step = {}, {}, None
    for name, obj in datasets:
        group, _, dataset = name.rpartition("/")
        if group == "coordinator" and dataset == "step":
            step = obj[:steps].astype(np.int64, copy=False)
            continue
        column = _column_name(group, dataset)
        columns[column] = obj[:steps].astype(np.float64, copy=False)  # one read, no second copy
        units[column] = obj.attrs["units"].decode() if isinstance(obj.attrs["units"], bytes) else str(obj.attrs["units"])
    return History(step, run_group.attrs["period_s"], columns, units)


def _open_h5(path):
    import h5py

    try:
        return h5py.File(path, "r")
    except OSError:
        # A run killed outright leaves the file marked open for writing; SWMR reads it as it is.
        return h5py.File(path, "r", libver="latest", swmr=True)


def _load_test(folder, summary, source):
    # A test's own results.h5, or a case's group in its sweep's or batch's file (its summary
    # names both: docs/results-format.md).
    h5, group = folder / "results.h5", "/"
    if not h5.exists() and "results_h5" in summary:
        h5, group = folder / summary["results_h5"], summary.get("results_h5_group", "/")
    csv_file = folder / "time_history.csv"
    if source is None:
        source = "hdf5" if h5.exists() else "csv"
    if source == "hdf5":
        if not h5.exists():
            raise ConfigError("%s: no results.h5 (the run wrote CSV: load(folder, source='csv'))" % folder)
        with _open_h5(h5) as f:
            if group not in f:
                raise ConfigError("%s: %s holds no group %s" % (folder, h5, group))
            g = f[group]
            test = _history_from_h5(g["test"]) if "test" in g else None
            reference = _history_from_h5(g["reference"]) if "reference" in g else None
        return Result(folder, summary, test, reference, "hdf5")
    if source != "csv":
        raise ConfigError("source: expected 'hdf5', 'csv' or None, got %r" % (source,))
    period_s = 1.0 / summary["control_rate_hz"] if summary.get("control_rate_hz") else float("nan")
    test = _history_from_csv(csv_file, period_s) if csv_file.exists() else None
    ref_file = folder / "reference_history.csv"
    reference = _history_from_csv(ref_file, period_s) if ref_file.exists() else None
    if test is None and h5.exists():
        raise ConfigError("%s: no time_history.csv (the run wrote results.h5: load(folder, source='hdf5'))" % folder)
    return Result(folder, summary, test, reference, "csv")


def _read_table(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    columns = {}
    for i, name in enumerate(header):
        cells = [row[i] if i < len(row) else "" for row in body]
        try:
            columns[name] = np.array([float(c) for c in cells], dtype=np.float64)
        except ValueError:
            columns[name] = cells
    return Table(columns)


def _load(folder, source=None, eager=False):
    folder = Path(folder)
    if not folder.is_dir():
        raise ConfigError("%s: no such folder" % folder)
    summary = _read_summary(folder)
    kind = summary.get("study")

    def cases(table_file, subfolders):
        names = []
        if table_file.exists():
            table = _read_table(table_file)
            names = list(table["folder"]) if "folder" in table else []
        if not names:
            names = sorted(p.name for p in folder.glob(subfolders) if (p / "summary.json").exists())
        found = _Cases([folder / n for n in names], lambda f: _load(f, source))
        if eager:
            for i in range(len(found)):
                found[i]
        return found

    if kind == "rpsd_test":
        return _load_test(folder, summary, source)
    if kind == "rpsd_test_sweep":
        table = _read_table(folder / "sweep.csv") if (folder / "sweep.csv").exists() else Table({})
        return Sweep(folder, summary, table, cases(folder / "sweep.csv", "case_*"))
    if kind == "rpsd_test_monte_carlo":
        table = _read_table(folder / "runs.csv") if (folder / "runs.csv").exists() else Table({})
        stats = folder / "statistics.csv"
        return MonteCarlo(folder, summary, table, _read_table(stats) if stats.exists() else Table({}),
                          cases(folder / "runs.csv", "run_*"))
    if kind is not None:
        return Study(folder, summary, {p.stem: _read_table(p) for p in sorted(folder.glob("*.csv"))})
    raise ConfigError("%s: summary.json says no study; not a folder rpsd run wrote" % folder)


def load(folder, source=None):
    """Reads a folder ``rpsd run`` (or :func:`rpsd.run`) wrote.

    Args:
        folder: the output folder (str or path-like).
        source: for a test, ``"hdf5"`` (results.h5) or ``"csv"`` (time_history.csv and
            reference_history.csv); ``None``: results.h5 when the folder has one. Both give the
            same arrays (the CSV rounds each value to 10 significant digits).

    Returns:
        :class:`rpsd.Result` for a test, :class:`rpsd.Sweep` for a sweep,
        :class:`rpsd.MonteCarlo` for a Monte Carlo batch (their cases and runs are read when
        first indexed), :class:`rpsd.Study` for one of the paper's studies.

    Raises:
        rpsd.ConfigError: the folder does not exist or rpsd did not write it.

    Example::

        r = rpsd.load("out/elcentro")
        r.test["measured_m_ch0"], r.test.units["measured_m_ch0"], r.criteria["channels"]
    """
    return _load(folder, source)
