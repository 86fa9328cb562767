"""Y6: errors become fdem.InputError / fdem.SimulationError with the CLI's messages."""
import pytest

import fdem
from conftest import ROOT, cli_run, example


def test_input_error_has_the_cli_message(tmp_path):
    text = open(example("01_cantilever")).read().replace("poisson_ratio", "poisson_rato", 1)
    path = tmp_path / "scenario.toml"
    path.write_text(text)
    (tmp_path / "x").mkdir()
    with pytest.raises(fdem.InputError) as e:
        fdem.Simulation.from_toml(str(path))
    assert isinstance(e.value, ValueError)
    assert e.value.line > 0 and e.value.column > 0 and e.value.file == str(path)
    assert "poisson_rato" in str(e.value)
    rc, _, err = cli_run(["run", str(path), "--out", str(tmp_path / "out")])
    assert rc == 2
    assert str(e.value) in err  # the same text the CLI prints


def test_missing_file():
    with pytest.raises(fdem.InputError, match="cannot open scenario file 'no_such.toml'"):
        fdem.Simulation.from_toml("no_such.toml")


def test_simulation_error_has_the_cli_message(tmp_path):
    crush = str(ROOT / "tests" / "cli" / "crush.toml")
    sim = fdem.Simulation.from_toml(crush)
    with pytest.raises(fdem.SimulationError) as e:
        sim.run()
    assert isinstance(e.value, RuntimeError)
    assert e.value.step > 0 and e.value.time > 0
    assert "triangle" in e.value.entity
    rc, _, err = cli_run(["run", crush, "--out", str(tmp_path / "out")])
    assert rc == 1
    assert str(e.value) in err
