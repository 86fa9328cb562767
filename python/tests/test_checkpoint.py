"""Y7: save at step 200, restore in a new simulation, run to 400: bitwise the uninterrupted run."""
import pytest

import fdem
from conftest import example


def test_restart_is_bitwise(tmp_path):
    ref = fdem.Simulation.from_toml(example("03_contact_slide"))
    end = 400 * ref.dt
    ref.end_time = end
    ref.run()

    a = fdem.Simulation.from_toml(example("03_contact_slide"))
    a.end_time = end
    a.run(steps=200)
    path = str(tmp_path / "run.fdck")
    a.save_checkpoint(path)
    a.run()  # the saver goes on unchanged
    assert a.state_hash() == ref.state_hash()

    b = fdem.Simulation.from_toml(example("03_contact_slide"))
    b.end_time = end
    x = b.state.x  # a view taken before the restore stays valid
    b.restore_checkpoint(path)
    assert b.step_count == 200
    assert (x == b.state.x).all()
    b.run()
    assert b.step_count == 400
    assert b.state_hash() == ref.state_hash()


def test_checkpoint_of_another_model_is_refused(tmp_path):
    a = fdem.Simulation.from_toml(example("03_contact_slide"))
    a.step(3)
    path = str(tmp_path / "run.fdck")
    a.save_checkpoint(path)
    other = fdem.Simulation.from_toml(example("01_cantilever"))
    with pytest.raises(fdem.InputError):
        other.restore_checkpoint(path)
    assert other.step_count == 0
