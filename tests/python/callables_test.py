"""Python callables as the parts a scenario names `kind: external` (rpsd.run(..., callables=...)):
a Python phase lead gives the YAML phase lead's history bit for bit, a Python linear structure
the YAML linear structure's; each run and channel has its own state; a Python exception ends the
run in order; a real-time clock and a missing callable are refused."""
import numpy as np
import pytest
import yaml

import rpsd
from conftest import SCENARIO, SHORT


class PhaseLead:
    """rpsd's phase lead (compensation/src/discrete_phase_lead.cpp), written out in Python:
    (1 + a T s) / (1 + T s) by Tustin, T = delay / (a - 1), the same operations in the same order."""

    def __init__(self, delay_s, ratio_a):
        self.delay_s, self.ratio_a = delay_s, ratio_a
        self.calls = 0

    def configure(self, dt_s):
        a, t = self.ratio_a, self.delay_s / (self.ratio_a - 1.0)
        k = 2.0 / dt_s
        den = 1.0 + t * k
        self.b0, self.b1, self.a1 = (1.0 + a * t * k) / den, (1.0 - a * t * k) / den, (1.0 - t * k) / den

    def reset(self, x0):
        self.u = self.y = x0

    def command(self, target_m):
        y = self.b0 * target_m + self.b1 * self.u - self.a1 * self.y
        self.u, self.y = target_m, y
        self.calls += 1
        return y


def scenario_with(compensation):
    s = yaml.safe_load(SCENARIO.read_text())
    s["compensation"] = compensation
    s["servo"]["parameters"] = str((SCENARIO.parent / s["servo"]["parameters"]).resolve())
    if "file" in s.get("ground_motion", {}):
        s["ground_motion"]["file"] = str((SCENARIO.parent / s["ground_motion"]["file"]).resolve())
    return s


def bits(a):
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)


def same_history(a, b):
    names = [n for n in a.columns if not n.startswith(("round_trip_s", "cycle_lateness_s"))]
    assert names == [n for n in b.columns if not n.startswith(("round_trip_s", "cycle_lateness_s"))]
    assert np.array_equal(a.step, b.step)
    return [n for n in names if not np.array_equal(bits(a[n]), bits(b[n]))]


def test_a_python_phase_lead_gives_the_yaml_phase_leads_history_bit_for_bit(scratch):
    yaml_lead = rpsd.run(scenario_with({"kind": "phase_lead", "delay_s": 0.09, "ratio_a": 20}),
                         out=scratch / "yaml", overrides=SHORT, format="hdf5")
    python_lead = rpsd.run(scenario_with({"kind": "external", "name": "lead"}), out=scratch / "python",
                           overrides=SHORT, format="hdf5", callables={"lead": PhaseLead(0.09, 20)})
    assert python_lead.test.steps == 2048
    assert same_history(python_lead.test, yaml_lead.test) == []
    assert python_lead.summary["compensation"] == "external"
    assert python_lead.summary["compensation_host_name"] == "lead"
    assert "compensation_host_name" not in yaml_lead.summary
    # The command really is the lead's, not the target's: the lead is seen in the record.
    assert not np.array_equal(python_lead.test["command_m_ch0"], python_lead.test["target_m_ch0"])


def test_each_run_gets_its_own_copy_of_the_object_and_the_object_given_is_untouched(scratch):
    given = PhaseLead(0.09, 20)
    first = rpsd.run(scenario_with({"kind": "external", "name": "lead"}), out=scratch / "a", overrides=SHORT,
                     format="hdf5", callables={"lead": given})
    second = rpsd.run(scenario_with({"kind": "external", "name": "lead"}), out=scratch / "b", overrides=SHORT,
                      format="hdf5", callables={"lead": given})
    assert given.calls == 0
    assert same_history(first.test, second.test) == []


class LinearFrame:
    """R(d) = K d with trial/commit, K the file's stiffness."""

    def __init__(self, k):
        self.k = np.array(k)
        self.commits = 0

    def restoring_force(self, d):
        return self.k @ d

    def commit(self):
        self.commits += 1


FRAME = {
    "study": "rpsd_test",
    "structure": {"kind": "linear", "mass_kg": [1000, 1000],
                  "stiffness_n_per_m": [[2.0e6, -1.0e6], [-1.0e6, 1.0e6]],
                  "damping": {"rayleigh": {"mode_a": 1, "mode_b": 2, "damping_ratio_a": 0.02, "damping_ratio_b": 0.02}}},
    "experimental": [{"dof": 0, "specimen_stiffness_n_per_m": 1.0e5, "restoring_force": "stiffness_times_displacement"}],
    "servo": {"kind": "ideal_delay", "delay_s": 0.01, "rig": {"stroke_m": 0.25, "force_n": 1.0e6, "velocity_m_per_s": 1.0}},
    "clock": {"mode": "as_fast_as_possible", "control_rate_hz": 1024},
    "free_vibration": {"initial_displacement_m": [0.001, 0.002], "duration_s": 1},
    "output": {"record_dofs": [0, 1]},
}


def frame(kind, **extra):
    s = yaml.safe_load(yaml.safe_dump(FRAME))
    s["structure"]["kind"] = kind
    s["structure"].update(extra)
    return s


@pytest.mark.parametrize("scheme", ["central_difference", "newmark"])
def test_a_python_linear_structure_gives_the_yaml_linear_structures_history_bit_for_bit(scratch, scheme):
    yaml_frame = frame("linear")
    yaml_frame["integrator"] = {"scheme": scheme}
    python_frame = frame("external", name="frame")
    python_frame["integrator"] = {"scheme": scheme}
    a = rpsd.run(yaml_frame, out=scratch / "yaml", format="hdf5")
    b = rpsd.run(python_frame, out=scratch / "python", format="hdf5",
                 callables={"frame": LinearFrame(FRAME["structure"]["stiffness_n_per_m"])})
    assert b.test.steps == 1024
    assert same_history(b.test, a.test) == []
    assert same_history(b.reference, a.reference) == []


class Failing(PhaseLead):
    def command(self, target_m):
        if self.calls == 499:
            raise RuntimeError("the participant's controller gave up")
        return super().command(target_m)


def test_a_python_exception_ends_the_run_in_order_and_names_itself(scratch):
    with pytest.raises(rpsd.TestStopped) as stopped:
        rpsd.run(scenario_with({"kind": "external", "name": "lead"}), out=scratch / "run", overrides=SHORT,
                 callables={"lead": Failing(0.09, 20)})
    summary = stopped.value.result.summary
    assert summary["stopped_by"]["kind"] == "host_call_failed"
    assert "the participant's controller gave up" in summary["stopped_by"]["host_says"]
    assert stopped.value.result.test.steps == summary["steps"] < 2048


def test_a_real_time_clock_and_a_missing_callable_are_refused_at_the_key(scratch):
    real_time = scenario_with({"kind": "external", "name": "lead"})
    real_time["clock"]["mode"] = "real_time"
    with pytest.raises(rpsd.ConfigError, match=r"compensation\.kind"):
        rpsd.run(real_time, out=scratch / "rt", callables={"lead": PhaseLead(0.09, 20)})
    with pytest.raises(rpsd.ConfigError, match=r"compensation\.name.*lead"):
        rpsd.run(scenario_with({"kind": "external", "name": "lead"}), out=scratch / "none", overrides=SHORT)


def test_a_plain_function_is_a_stateless_compensator_and_the_dry_run_calls_it(scratch):
    def pass_through(target_m):
        return target_m

    s = scenario_with({"kind": "external", "name": "plain"})
    a = rpsd.run(s, out=scratch / "plain", overrides=SHORT, format="hdf5", callables={"plain": pass_through})
    assert np.array_equal(a.test["command_m_ch0"], a.test["target_m_ch0"])
    report = rpsd.dry_run(SCENARIO, overrides={**SHORT, "compensation": "{kind: external, name: plain}"},
                          callables={"plain": pass_through})
    assert "ready" in report
