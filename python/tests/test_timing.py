"""Step timing from Python (docs/python.md): sim.timing_on, sim.timing, sim.reset_timing();
timing off reads no clock and records nothing, and no bit of a run depends on it."""
import fdem
from conftest import example

PHASES = ["elements", "joints", "broad_phase", "narrow_phase", "contact_apply", "node_update",
          "communication"]


def run(on, steps=300):
    sim = fdem.Simulation.from_toml(example("03_contact_slide"))
    sim.timing_on = on
    sim.run(steps=steps)
    return sim


def test_off_records_nothing():
    sim = run(False)
    assert sim.timing_on is False
    t = sim.timing
    assert t["steps"] == 0
    assert all(t[p] == 0.0 for p in PHASES)


def test_on_records_the_phases_and_changes_no_bit():
    off, on = run(False), run(True)
    assert on.state_hash() == off.state_hash()
    t = on.timing
    assert sorted(t) == sorted(PHASES + ["steps"])
    assert t["steps"] == 300
    assert all(t[p] >= 0.0 for p in PHASES)
    # example 03: a block sliding on a base, so elements, contact and the node update all run
    for p in ["elements", "narrow_phase", "contact_apply", "node_update"]:
        assert t[p] > 0.0, p
    assert t["joints"] == 0.0 and t["communication"] == 0.0  # no joints, one process
    on.reset_timing()
    assert on.timing["steps"] == 0 and on.timing["elements"] == 0.0
