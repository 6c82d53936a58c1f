"""The exceptions rpsd raises, one per exit code of the command line (README, "Exit codes").

Every one carries the command line's message, and is a subclass of :class:`rpsd.Error`.
"""
import re

__all__ = ["Error", "ConfigError", "TestStopped", "NotReady", "ResultsNotWritten"]


class Error(Exception):
    """Anything rpsd refuses or fails at (exit code 1 when no subclass fits: an internal error)."""

    exit_code = 1


# "rig.yaml:12:3: specimen.mass_kg: expected ..." or "--set #1 (k=v): k: expected ..." or
# "overrides['k'] (k=v): k: ..." (rpsd/scenarios/config_error.h).
_AT_FILE = re.compile(r"^(?P<file>.+?):(?P<line>\d+):(?P<column>\d+): (?P<key>[^\s:]+): ")
_AT_OVERRIDE = re.compile(r"^(?P<origin>.+?) \((?P<text>.*?)\): (?P<key>[^\s:]+): ")


class ConfigError(Error, ValueError):
    """Bad input (exit code 2): a file, key, value or option is wrong, or ``out`` holds another run.

    Attributes, ``None`` where the message does not say: ``file``, ``line`` and ``column`` (1-based)
    of the value at fault, ``key`` (its key path, e.g. ``structure.mass_kg``) and ``origin`` (the
    override that gave it, e.g. ``overrides['structure.mass_kg']``).
    """

    exit_code = 2

    def __init__(self, message):
        super().__init__(message)
        self.file = self.line = self.column = self.key = self.origin = None
        m = _AT_FILE.match(message)
        if m:
            self.file, self.key = m["file"], m["key"]
            self.line, self.column = int(m["line"]), int(m["column"])
            return
        m = _AT_OVERRIDE.match(message)
        if m:
            self.origin, self.key = m["origin"], m["key"]


class TestStopped(Error):
    """The test stopped before its end (exit code 3): a limit, a run-away, a node or link failure.

    A stopped test still has data: ``result`` is the :class:`rpsd.Result` of every step it took
    (its ``summary["result"]`` is ``"stopped"``; ``summary["stopped_by"]`` says why).
    """

    exit_code = 3
    __test__ = False  # not a pytest test class

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


class NotReady(Error):
    """Not ready (exit code 4): no servo node answered before the first step, nothing moved."""

    exit_code = 4

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


class ResultsNotWritten(Error):
    """A result file could not be written (exit code 5): a full disk, permissions.

    ``result`` holds what could be read back (``None`` if nothing could).
    """

    exit_code = 5

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result
