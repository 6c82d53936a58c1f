"""What rpsd.load and rpsd.run return: a test's time histories as NumPy arrays with their
units, its summary and criteria; a sweep's, a Monte Carlo batch's and a study's tables.

Every object is read whole when it is made (a test's arrays included), except the cases of a
sweep and the runs of a batch loaded from a folder, which are read when first indexed.
"""
from collections.abc import Mapping, Sequence
from pathlib import Path

__all__ = ["History", "Result", "Table", "Sweep", "MonteCarlo", "Study"]


class _Columns(Mapping):
    """Column name -> array, in the file's order; columns read as attributes too."""

    def __init__(self, columns):
        self._columns = dict(columns)

    def __getitem__(self, name):
        return self._columns[name]

    def __iter__(self):
        return iter(self._columns)

    def __len__(self):
        return len(self._columns)

    def __getattr__(self, name):
        columns = self.__dict__.get("_columns", {})
        if name in columns:
            return columns[name]
        raise AttributeError(name)

    @property
    def columns(self):
        """The column names, in the file's order."""
        return list(self._columns)


class History(_Columns):
    """One run's time histories: column name -> 1-D ``numpy.float64`` array, one value per step.

    The columns are those of ``time_history.csv`` (e.g. ``measured_m_ch0``,
    ``displacement_m_dof0``, ``input_energy_j``), whether read from results.h5 or the CSV;
    ``units[name]`` is each column's unit (``"m"``, ``"N"``, ``"m/s^2"``, ``"1"`` for a count or
    flag word). ``step`` is the step index (``int64``), ``time_s`` the step times the period
    ``period_s``. Columns read as attributes too: ``h.measured_m_ch0``.
    """

    def __init__(self, step, period_s, columns, units):
        super().__init__(columns)
        self.step = step
        self.period_s = float(period_s)
        self.time_s = step * self.period_s
        self.units = dict(units)

    @property
    def steps(self):
        """How many steps the history holds."""
        return len(self.step)

    def __repr__(self):
        return "History(%d steps of %g s, %d columns)" % (self.steps, self.period_s, len(self))


class Result:
    """A test's results (one folder ``rpsd run`` wrote for an ``rpsd_test`` scenario).

    Attributes: ``test`` and ``reference`` (:class:`History`; ``reference`` is the run with a
    perfect actuator, ``None`` where the test has none; ``test`` is ``None`` for a run whose
    histories were not kept), ``summary`` (``summary.json`` as a dict), ``criteria`` (the
    criteria of summary.json: ``channels``, ``dofs``, ``benchmark_criteria``), ``folder``
    (``pathlib.Path``), ``source`` (``"hdf5"`` or ``"csv"``: what the histories were read from).
    """

    def __init__(self, folder, summary, test, reference, source):
        self.folder = Path(folder)
        self.summary = summary
        self.criteria = {k: summary[k] for k in ("channels", "dofs", "benchmark_criteria") if k in summary}
        self.test = test
        self.reference = reference
        self.source = source

    @property
    def result(self):
        """summary.json's ``result``: completed, stopped, interrupted, results_not_written, not_ready."""
        return self.summary.get("result")

    @property
    def completed(self):
        return self.result == "completed"

    def __repr__(self):
        return "Result(%r, %s, %s)" % (str(self.folder), self.result, self.test)


class Table(_Columns):
    """A CSV table rpsd wrote (sweep.csv, runs.csv, statistics.csv, a study's tables): column ->
    ``numpy.float64`` array, or a list of ``str`` for a column of words (``folder``)."""

    @property
    def rows(self):
        return len(next(iter(self._columns.values()))) if self._columns else 0

    def __repr__(self):
        return "Table(%d rows, columns %s)" % (self.rows, ", ".join(self._columns))


class _Cases(Sequence):
    """A sweep's cases or a batch's runs, each a :class:`Result` read when first indexed."""

    def __init__(self, folders, load):
        self._folders = list(folders)
        self._load = load
        self._loaded = {}

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(len(self)))]
        i = range(len(self._folders))[i]
        if i not in self._loaded:
            self._loaded[i] = self._load(self._folders[i])
        return self._loaded[i]

    def __len__(self):
        return len(self._folders)

    @property
    def folders(self):
        return list(self._folders)


class _Batch:
    """What a sweep and a Monte Carlo batch share: ``folder``, ``summary``, ``table`` (one row
    per run) and the runs, each a :class:`Result`."""

    _noun = "runs"

    def __init__(self, folder, summary, table, runs):
        self.folder = Path(folder)
        self.summary = summary
        self.table = table
        self._runs = runs

    @property
    def result(self):
        """summary.json's ``result``."""
        return self.summary.get("result")

    def __repr__(self):
        return "%s(%r, %d %s, %s)" % (type(self).__name__, str(self.folder), len(self._runs), self._noun, self.result)


class Sweep(_Batch):
    """A sweep (``sweep:`` in a scenario): ``table`` (sweep.csv: each case's swept values and
    headline numbers), ``cases`` (a :class:`Result` per case, in the table's order),
    ``summary``, ``folder``."""

    _noun = "cases"

    @property
    def cases(self):
        return self._runs


class MonteCarlo(_Batch):
    """A Monte Carlo batch (``monte_carlo:``): ``table`` (runs.csv: each run's drawn values,
    outcome and criteria), ``statistics`` (statistics.csv), ``runs`` (a :class:`Result` per
    run), ``summary``, ``folder``."""

    def __init__(self, folder, summary, table, statistics, runs):
        super().__init__(folder, summary, table, runs)
        self.statistics = statistics

    @property
    def runs(self):
        return self._runs


class Study:
    """One of the seed paper's studies (Figures 5-8: ``study: servo_sine_sweep``, ...):
    ``kind`` (summary.json's ``study``), ``tables`` (each CSV table of the folder by its name
    without ``.csv``, e.g. ``damping`` for Figure 8), ``summary``, ``folder``."""

    def __init__(self, folder, summary, tables):
        self.folder = Path(folder)
        self.summary = summary
        self.kind = summary.get("study")
        self.tables = tables

    def __repr__(self):
        return "Study(%r, %s, tables %s)" % (str(self.folder), self.kind, ", ".join(self.tables))
