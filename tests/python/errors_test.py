"""Errors raise rpsd's exceptions with the command line's messages: file:line:column and key."""
import shutil
from pathlib import Path

import pytest
import yaml

import rpsd
from conftest import SCENARIO, SCENARIOS, SHORT


def test_a_bad_key_names_file_line_and_key(scratch):
    bad = scratch / "bad.yaml"
    bad.write_text(SCENARIO.read_text().replace("  mass_kg: 7080", "  mass_kgx: 7080"))
    line = next(i for i, text in enumerate(bad.read_text().splitlines(), 1) if "mass_kgx" in text)
    with pytest.raises(rpsd.ConfigError) as caught:
        rpsd.run(bad, out=scratch / "out", overrides=SHORT)
    e = caught.value
    assert str(e).startswith("%s:%d:3: structure.mass_kgx: unknown key" % (bad, line))
    assert (e.file, e.line, e.column, e.key, e.exit_code) == (str(bad), line, 3, "structure.mass_kgx", 2)
    assert isinstance(e, rpsd.Error) and isinstance(e, ValueError)


def test_a_bad_override_names_it():
    with pytest.raises(rpsd.ConfigError) as caught:
        rpsd.validate(SCENARIO, overrides={"structure.mass_kg": -3})
    assert caught.value.origin == "overrides['structure.mass_kg']"
    assert caught.value.key == "structure.mass_kg" and "expected a number" in str(caught.value)


def test_a_bad_key_in_a_dict_names_the_line_of_its_scenario_yaml(scratch):
    scenario = yaml.safe_load(SCENARIO.read_text())
    for section, key in (("servo", "parameters"), ("ground_motion", "file")):
        scenario[section][key] = str((SCENARIOS / scenario[section][key]).resolve())
    scenario["structure"]["mas_kg"] = scenario["structure"].pop("mass_kg")
    with pytest.raises(rpsd.ConfigError) as caught:
        rpsd.run(scenario, out=scratch / "out", overrides=SHORT)
    written = scratch / "out/scenario.yaml"
    line = next(i for i, text in enumerate(written.read_text().splitlines(), 1) if "mas_kg" in text)
    assert (caught.value.file, caught.value.line, caught.value.key) == (str(written), line, "structure.mas_kg")
    # Corrected, it runs into the same folder (the scenario.yaml left there is its own).
    scenario["structure"]["mass_kg"] = scenario["structure"].pop("mas_kg")
    assert rpsd.run(scenario, out=scratch / "out", overrides=SHORT).completed


def test_without_out_the_dicts_scenario_yaml_the_error_names_is_still_there():
    scenario = yaml.safe_load(SCENARIO.read_text())
    scenario["structure"]["mas_kg"] = scenario["structure"].pop("mass_kg")
    with pytest.raises(rpsd.ConfigError) as caught:
        rpsd.run(scenario, overrides=SHORT)
    named = Path(caught.value.file)
    try:
        assert caught.value.key == "structure.mas_kg" and named.name == "scenario.yaml"
        assert "mas_kg" in named.read_text().splitlines()[caught.value.line - 1]
    finally:
        shutil.rmtree(named.parent, ignore_errors=True)


def test_a_missing_file_names_it(scratch):
    with pytest.raises(rpsd.ConfigError, match="nothing-here.yaml: does not exist"):
        rpsd.run(scratch / "nothing-here.yaml", out=scratch / "out")
    with pytest.raises(rpsd.ConfigError, match="ground_motion.file: no such record file: .*no-record.AT2"):
        rpsd.run(SCENARIO, out=scratch / "out2", record=scratch / "no-record.AT2")


def test_an_output_folder_in_use_is_refused(scratch):
    (scratch / "out").mkdir()
    (scratch / "out/notes.txt").write_text("mine")
    with pytest.raises(rpsd.ConfigError, match="not empty"):
        rpsd.run(SCENARIO, out=scratch / "out", overrides=SHORT)
    assert (scratch / "out/notes.txt").read_text() == "mine"


def test_a_stopped_test_raises_test_stopped_with_its_data(scratch):
    # A stroke limit of 0.1 mm: El Centro's response passes it within the first seconds.
    with pytest.raises(rpsd.TestStopped) as caught:
        rpsd.run(SCENARIO, out=scratch / "out", overrides={**SHORT, "experimental.0.limits.max_stroke_m": 1e-4})
    e = caught.value
    assert e.exit_code == 3 and "every recorded step is in" in str(e)
    assert e.result.summary["result"] == "stopped"
    steps = e.result.test.steps
    assert 0 < steps < 2048 and steps == e.result.summary["steps"]
    # Every recorded command is within the limit: the stop acted before one was sent beyond it.
    assert abs(e.result.test["command_m_ch0"]).max() <= 1e-4
