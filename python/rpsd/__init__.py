"""rpsd from Python: run real-time hybrid (pseudodynamic) test scenarios in this process and read
their results as NumPy arrays with units (docs/python.md).

Functions:
    run(scenario, out=None, overrides=None, record=None, format=None) -- a scenario run as
        ``rpsd run`` does; returns its results.
    load(folder, source=None) -- any folder rpsd wrote (a test, a sweep, a Monte Carlo batch, a
        study), CSV or results.h5.
    validate(path, overrides=None), dry_run(path, overrides=None, nodes=None),
    analyze_servo(path), integrator_properties(name, omega_dt, ...) -- what the command line's
        ``--json`` prints, as dicts.

Exceptions (all rpsd.Error, each with the command line's message and ``exit_code``):
    ConfigError (bad input, 2), TestStopped (3), NotReady (4), ResultsNotWritten (5).
    Ctrl-C during a run stops it in order and raises KeyboardInterrupt.

Example::

    import rpsd
    r = rpsd.run("examples/scenarios/elcentro-sdof.yaml", overrides={"ground_motion.trim.end_s": 5})
    r.test["measured_m_ch0"], r.test.units["measured_m_ch0"], r.summary["result"]
"""
from . import _rpsd
from .checks import analyze_servo, dry_run, integrator_properties, validate
from .errors import ConfigError, Error, NotReady, ResultsNotWritten, TestStopped
from .loader import load
from .results import History, MonteCarlo, Result, Study, Sweep, Table
from .running import run

__version__ = _rpsd.version
__commit__ = _rpsd.commit

__all__ = ["run", "load", "validate", "dry_run", "analyze_servo", "integrator_properties",
           "Error", "ConfigError", "TestStopped", "NotReady", "ResultsNotWritten",
           "Result", "History", "Sweep", "MonteCarlo", "Study", "Table"]
