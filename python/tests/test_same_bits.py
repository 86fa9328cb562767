"""Y2: Python runs are bitwise the CLI's runs (same hash)."""
import pytest

import fdem
from conftest import cli_hash, example


@pytest.mark.parametrize("name,steps", [("01_cantilever", 400), ("03_contact_slide", 400)])
def test_run_equals_cli(name, steps, tmp_path):
    sim = fdem.Simulation.from_toml(example(name))
    end = steps * sim.dt
    sim.end_time = end
    res = sim.run(until=end)
    assert res == {"status": "reached", "steps": steps}
    assert sim.state_hash() == cli_hash(example(name), end, tmp_path / "cli")


def test_run_in_pieces_with_callbacks_is_bitwise(tmp_path):
    a = fdem.Simulation.from_toml(example("03_contact_slide"))
    b = fdem.Simulation.from_toml(example("03_contact_slide"))
    end = 300 * a.dt
    a.end_time = b.end_time = end
    a.run(until=end)
    seen = []
    b.run(steps=100, callback=lambda s: seen.append(s.step_count), every=25)
    b.run(until=end)
    assert seen == [25, 50, 75, 100]
    assert a.state_hash() == b.state_hash()


def test_callback_can_stop_the_run():
    sim = fdem.Simulation.from_toml(example("03_contact_slide"))
    res = sim.run(until=1.0, callback=lambda s: s.step_count < 30, every=10)
    assert res == {"status": "callback_stopped", "steps": 30}
    assert sim.step_count == 30


def test_callback_exception_propagates():
    sim = fdem.Simulation.from_toml(example("03_contact_slide"))

    def bad(s):
        raise KeyError("from the callback")

    with pytest.raises(KeyError, match="from the callback"):
        sim.run(steps=50, callback=bad, every=5)
    assert sim.step_count == 5  # stopped after the step whose callback raised
