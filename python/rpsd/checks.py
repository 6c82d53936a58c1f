"""rpsd.validate, rpsd.dry_run, rpsd.analyze_servo, rpsd.integrator_properties: what the command
line's ``--json`` prints, from the same C++ code, as Python objects."""
import json
import os

from . import _rpsd
from ._convert import override_texts

__all__ = ["validate", "dry_run", "analyze_servo", "integrator_properties"]


def validate(path, overrides=None, callables=None):
    """Reads and checks a scenario, a site-server file or a servo node's file without running it.

    Returns what ``rpsd validate FILE --json`` prints, as a dict: ``kind`` (``rpsd_test``,
    ``sweep``, ``monte_carlo``, ``study``, ``site_server`` or ``servo_node``), ``file``, ``ok``,
    ``overview`` (the text's lines) and the kind's fields; for a test, ``test`` holds the
    structure's modes, the steps, the record and each channel's envelope and limits.

    Args:
        path: the file. overrides: ``{"key.path": value}`` as ``--set``.
        callables: ``{name: object}`` for the parts the scenario names ``kind: external``
            (as :func:`rpsd.run`); without them such a scenario is refused at the name.

    Raises:
        rpsd.ConfigError: the message names file:line:column and the key path.

    Example::

        v = rpsd.validate("examples/scenarios/elcentro-sdof.yaml")
        v["test"]["structure_modes"][0]["frequency_hz"]
    """
    return json.loads(_rpsd.validate_json(os.fspath(path), override_texts(overrides), dict(callables or {})))


def dry_run(path, overrides=None, nodes=None, callables=None):
    """The pre-test check of a test scenario: ``rpsd run FILE --dry-run --json``.

    Runs the test against the simulated plant in this process and returns the predicted peaks
    against each limit, the damping per mode and the verdict, as a dict (what dry-run.json
    holds). A test that is not ready is not an exception here: ``report["ready"]`` is False
    (the command line exits with code 4).

    Args:
        path: an ``rpsd_test`` scenario. overrides: ``{"key.path": value}`` as ``--set``.
        nodes: servo node files (``--node``) whose limits are checked too.
        callables: ``{name: object}`` for the parts the scenario names ``kind: external``
            (as :func:`rpsd.run`): the dry run calls them as the test would.

    Raises:
        rpsd.ConfigError: a bad file or key, or a file that is not an ``rpsd_test`` scenario.
    """
    node_files = [os.fspath(n) for n in (nodes or [])]
    return json.loads(_rpsd.dry_run_json(os.fspath(path), override_texts(overrides), node_files,
                                         dict(callables or {})))


def analyze_servo(path):
    """The linear analysis of a servo-system parameter file: ``rpsd analyze FILE --json`` as a
    dict (cut-off frequency, response delay, the largest stable P gain, ...).

    Raises:
        rpsd.ConfigError: a bad file or key.
    """
    return json.loads(_rpsd.analyze_servo_json(os.fspath(path)))


def integrator_properties(name, omega_dt, damping=0.0, rho_inf=None, alpha=None):
    """The amplification-matrix properties of a time integrator on an SDOF:
    ``rpsd analyze integrator NAME --omega-dt ... --json`` as a dict.

    Args:
        name: the scheme or one of its spellings (``"central_difference"``, ``"hht"``, ...).
        omega_dt: Omega = omega dt, one value or a sequence of them.
        damping: the SDOF's physical damping ratio, in [0, 1).
        rho_inf, alpha: the scheme's parameter (``--rho-inf``, ``--alpha``), for the schemes that take it.

    Returns:
        a dict: ``scheme``, ``parameters``, ``stability_limit_omega_dt``, and ``points`` (per
        Omega the spectral radius, period ratio, numerical and algorithmic damping, eigenvalues).

    Raises:
        rpsd.ConfigError: an unknown scheme, a parameter it does not take, a value out of range.

    Example::

        p = rpsd.integrator_properties("hht", [0.1, 1.0], rho_inf=0.8)
        [q["spectral_radius"] for q in p["points"]]
    """
    values = [float(omega_dt)] if isinstance(omega_dt, (int, float)) else [float(w) for w in omega_dt]
    text = lambda x: None if x is None else repr(float(x))  # noqa: E731
    return json.loads(_rpsd.integrator_properties_json(name, values, float(damping), text(rho_inf), text(alpha)))
