"""validate, dry_run, analyze_servo and integrator_properties return what the command line's
--json prints: the same content, from the same code."""
import json

import rpsd
from conftest import SCENARIO, SHORT, SHORT_SET, SRC, cli

NODE = SRC / "examples/nodes/bridge-pier-site-1.yaml"


def test_validate_returns_what_validate_json_prints():
    for path, overrides, sets in ((SCENARIO, SHORT, SHORT_SET),
                                  (SRC / "examples/scenarios/elcentro-sdof-compensation-sweep.yaml", None, []),
                                  (NODE, None, [])):
        expected = json.loads(cli("validate", path, "--json", *sets))
        assert rpsd.validate(str(path), overrides=overrides) == expected
    v = rpsd.validate(str(SCENARIO), overrides=SHORT)
    assert v["kind"] == "rpsd_test" and v["test"]["steps"] == 2048
    assert abs(v["test"]["structure_modes"][0]["frequency_hz"] - 1.583) < 1e-3


def test_validate_json_says_what_the_text_says():
    text = cli("validate", SCENARIO).splitlines()
    assert json.loads(cli("validate", SCENARIO, "--json"))["overview"] == text[1:]


def test_dry_run_returns_what_the_dry_run_json_prints(scratch):
    expected = json.loads(cli("run", SCENARIO, "--dry-run", "--json", *SHORT_SET))
    report = rpsd.dry_run(SCENARIO, overrides=SHORT)
    assert report == expected and report["ready"] is True
    # The same numbers dry-run.json holds.
    cli("run", SCENARIO, "--dry-run", "--out", scratch / "dry", *SHORT_SET)
    assert json.loads((scratch / "dry/dry-run.json").read_text()) == report


def test_a_dry_run_that_is_not_ready_says_so_without_raising():
    tight = {**SHORT, "experimental.0.limits.max_stroke_m": 1e-4}
    expected = json.loads(cli("run", SCENARIO, "--dry-run", "--json", *SHORT_SET,
                              "--set", "experimental.0.limits.max_stroke_m=1e-4", expect=4))
    report = rpsd.dry_run(SCENARIO, overrides=tight)
    assert report == expected and report["ready"] is False


def test_analyze_servo_returns_what_analyze_json_prints():
    servo = SRC / "examples/servo/paper-mts-244.yaml"
    expected = json.loads(cli("analyze", servo, "--json"))
    got = rpsd.analyze_servo(servo)
    assert got == expected and abs(got["cutoff_frequency_hz"] - 1.959) < 1e-3


def test_integrator_properties_return_what_analyze_integrator_json_prints():
    expected = json.loads(cli("analyze", "integrator", "generalized_alpha", "--omega-dt", "0.1,1,3", "--rho-inf", "0.8",
                              "--damping", "0.05", "--json"))
    got = rpsd.integrator_properties("generalized_alpha", [0.1, 1, 3], damping=0.05, rho_inf=0.8)
    hht = json.loads(cli("analyze", "integrator", "hht", "--omega-dt", "0.5", "--alpha", "-0.2", "--json"))
    assert rpsd.integrator_properties("hht", 0.5, alpha=-0.2) == hht
    assert got == expected and len(got["points"]) == 3
    cd = rpsd.integrator_properties("central_difference", 2.5)
    assert cd["points"][0]["stable"] is False and cd["stability_limit_omega_dt"]["analytic_undamped"] == 2.0


def test_an_unknown_integrator_is_bad_input():
    try:
        rpsd.integrator_properties("euler", 0.1)
    except rpsd.ConfigError as e:
        assert "unknown integrator 'euler'" in str(e)
    else:
        raise AssertionError("no ConfigError")
