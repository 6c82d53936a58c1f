"""rpsd.run: a scenario run in this process through the command line's own code."""
import os
import shutil
import tempfile
from collections.abc import Mapping
from pathlib import Path

from . import _rpsd, errors
from ._convert import override_texts, plain
from .loader import _load

__all__ = ["run"]


def _write_scenario(scenario, out):
    import yaml

    # What an earlier attempt with this dict left (a bad key): ours to replace.
    if out.is_dir() and [p.name for p in out.iterdir()] == ["scenario.yaml"]:
        (out / "scenario.yaml").unlink()
    _rpsd.prepare_folder(str(out))
    path = out / "scenario.yaml"
    path.write_text(yaml.safe_dump(plain(scenario), sort_keys=False, default_flow_style=False))
    return path


def run(scenario, out=None, overrides=None, record=None, format=None, callables=None):
    """Runs a scenario in this process, as ``rpsd run SCENARIO --out OUT`` does, and returns its results.

    The run goes through the same code as the command line (the same files are written), on a
    thread of its own with the GIL released. Ctrl-C (SIGINT) stops it in order after the step
    under way, as on the command line: the folder's summary.json says ``interrupted``, and
    ``KeyboardInterrupt`` is raised once the run has ended.

    Args:
        scenario: a scenario file (str or path-like), or a dict holding one (written as YAML to
            ``OUT/scenario.yaml`` first, so that errors name its lines; file names in it are
            relative to OUT: give absolute ones).
        out: the output folder: created if missing, refused if it holds anything. ``None``: a
            temporary folder, removed once the results are read into memory.
        overrides: ``{"key.path": value}``, as ``--set key.path=value`` (later keys win), e.g.
            ``{"ground_motion.trim.end_s": 5, "compensation.delay_s": 0.08}``.
        record: a PEER AT2 file that replaces the scenario's record, its processing kept (``--record``).
        format: ``"csv"``, ``"hdf5"`` or ``"both"`` (``--format``). ``None``: ``"both"`` for a
            single test (results.h5 and the CSV tables with their plots); a sweep or a Monte Carlo
            batch writes CSV.
        callables: ``{name: object}``: the compensators (controllers) and numerical
            substructures the scenario names with ``kind: external`` and ``name``, for rehearsals
            (as fast as possible or lock-step; a real-time clock is refused). Each run, and each
            channel of a compensator, gets its own ``copy.deepcopy`` of the object (a class is
            called with no arguments instead), so state kept on ``self`` lasts from step to step
            and never leaks between runs or channels.

            - a compensator has ``command(target_m) -> command_m`` (or is itself callable with
              the target), and may have ``configure(dt_s)``, ``reset(initial_displacement_m)``
              and ``observe(target_m, measured_m)`` (called after each step's command);
            - a structure has ``restoring_force(d) -> r`` (NumPy vectors, one entry per DOF,
              always from the last committed state: an implicit scheme tries several ``d`` in a
              step), and may have ``commit()`` (the last trial is the step's state) and
              ``tangent_stiffness() -> K`` (else the file's initial stiffness serves). The file
              gives its mass, damping and initial stiffness as the linear kind does.

            The test runs on a thread of its own; each call takes the GIL. An exception raised
            in one ends the run in order after the step (``rpsd.TestStopped``; ``summary.json``
            ``stopped_by.kind: host_call_failed`` with the exception's text).

    Returns:
        what :func:`rpsd.load` returns for the folder: :class:`rpsd.Result` for a test (its
        ``test`` and ``reference`` histories as NumPy arrays with ``units``, ``summary``,
        ``criteria``, ``folder``), :class:`rpsd.Sweep`, :class:`rpsd.MonteCarlo` or
        :class:`rpsd.Study`.

    Raises:
        rpsd.ConfigError: bad input (exit code 2): the message names file:line:column and the
            key path, or the override, e.g. ``s.yaml:11:3: structure.mass_kgx: unknown key``.
        rpsd.TestStopped: the test stopped before its end (a limit, a run-away; exit code 3);
            its ``result`` holds every step taken.
        rpsd.NotReady: no servo node answered before the first step (exit code 4).
        rpsd.ResultsNotWritten: a result file could not be written (exit code 5).
        KeyboardInterrupt: Ctrl-C; the run stopped in order and its folder says ``interrupted``.

    Example::

        import rpsd
        r = rpsd.run("examples/scenarios/elcentro-sdof.yaml", out="out/elcentro",
                     overrides={"ground_motion.trim.end_s": 5})
        x = r.test["measured_m_ch0"]            # numpy.float64, one value per step
        print(r.test.units["measured_m_ch0"])   # "m"
        print(r.criteria["channels"][0]["j2_rms_tracking_error_percent"])
    """
    temporary = out is None
    out = Path(tempfile.mkdtemp(prefix="rpsd-run-")) if temporary else Path(os.fspath(out))
    keep = False
    try:
        prepare = True
        if isinstance(scenario, Mapping):
            scenario_file = _write_scenario(scenario, out)
            prepare = False
        else:
            scenario_file = Path(os.fspath(scenario))
        done = _rpsd.run_scenario(str(scenario_file), str(out), override_texts(overrides),
                                  os.fspath(record) if record is not None else "", format or "", prepare,
                                  dict(callables or {}))
        result = _load(out, eager=temporary)
        if "error" in done:
            if done["error_class"] == "KeyboardInterrupt":
                raise KeyboardInterrupt(done["error"])
            raise getattr(errors, done["error_class"])(done["error"], result)
        return result
    except errors.ConfigError as e:
        # A bad key in a dict names the line of the YAML written from it: without `out` that file
        # stays, so that the file:line the message gives can be read.
        keep = temporary and isinstance(scenario, Mapping) and str(out) in str(e)
        if not keep:
            raise
        raise errors.ConfigError(str(e) + " (the scenario written from the dict is kept there)") from None
    finally:
        if temporary and not keep:
            shutil.rmtree(out, ignore_errors=True)
