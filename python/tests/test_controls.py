"""Y5: support controls between steps (spec P5): a velocity changed at step 100 equals a scenario
whose support is split into two time windows at that step; switching a support off equals a
window that ends there; controls survive a checkpoint."""
import numpy as np
import pytest

import fdem

DT = 1.0e-5  # s, given (not "auto") so that the window boundary is the same step in both
V1, V2 = (0.5, 0.0), (-0.2, 0.3)  # m/s


def bar(windows):
    """A bar held at its left edge, its right edge driven; windows: [(velocity, start, end)]."""
    b = fdem.ModelBuilder(name="controls")
    b.simulation(end_time=300 * DT, dt=DT)
    m = b.material("m", density=1000.0, youngs_modulus=1e8, poisson_ratio=0.3)
    b.body("bar", mesh=fdem.Mesh.rectangle(0.0, 0.0, 1.0, 0.1, 20, 2), material=m)
    b.boundary("bar", "left", fix=["x", "y"])
    for v, start, end in windows:
        b.boundary("bar", "right", velocity=v, start=start, end=end)
    return b.build()


T100 = 100 * DT  # the time after 100 steps: step 100 is the first one of the second window


def test_velocity_change_equals_split_windows():
    a = bar([(V1, 0.0, None)])
    a.run(steps=100)
    sup = a.supports["bar/right"]
    assert sup.velocity == V1 and sup.active and sup.components == ["x", "y"]
    sup.velocity = V2
    assert a.state.bc_velocity[1].tolist() == list(V2)  # the view of the same control
    a.run(steps=200)

    b = bar([(V1, 0.0, T100), (V2, T100, None)])
    assert b.supports["bar/right"].windows == [(0.0, T100), (T100, np.inf)]
    b.run(steps=300)
    assert a.state_hash() == b.state_hash()
    right = a.supports["bar/right"].nodes
    np.testing.assert_array_equal(a.state.v[right], np.tile(V2, (len(right), 1)))


def test_switching_off_equals_a_window_end():
    a = bar([(V1, 0.0, None)])
    a.run(steps=100)
    a.supports["bar/right"].active = False
    a.run(steps=200)
    b = bar([(V1, 0.0, T100)])
    b.run(steps=300)
    assert a.state_hash() == b.state_hash()
    assert not a.supports["bar/right"].active
    assert a.state.bc_enabled.tolist() == [1, 0]


def test_controls_are_in_checkpoints(tmp_path):
    ref = bar([(V1, 0.0, None)])
    ref.run(steps=100)
    ref.supports["bar/right"].velocity = V2
    ref.run(steps=200)

    a = bar([(V1, 0.0, None)])
    a.run(steps=100)
    a.supports["bar/right"].velocity = V2
    a.save_checkpoint(str(tmp_path / "c.fdck"))
    b = bar([(V1, 0.0, None)])
    b.restore_checkpoint(str(tmp_path / "c.fdck"))
    assert b.supports["bar/right"].velocity == V2
    b.run(steps=200)
    assert b.state_hash() == ref.state_hash()


def test_bad_control_values():
    a = bar([(V1, 0.0, None)])
    with pytest.raises(ValueError, match="finite"):
        a.supports["bar/right"].velocity = (float("nan"), 0.0)
    with pytest.raises(KeyError):
        a.supports["bar/top"]


def test_energies_read_by_a_callback_are_fresh():
    """run() evaluates every energy on the steps a Python callback is called (the strain energy is
    otherwise skipped between output steps and would be stale there): an undamped bar driven by
    its support control, with an initial velocity field that matches both supports, keeps its
    recorded balance at round-off level (a stale strain energy gave 6e-3 of the scale)."""
    b = fdem.ModelBuilder(name="undamped")
    b.simulation(end_time=400 * DT, dt=DT, gravity=(0.0, -9.81))
    m = b.material("m", density=1000.0, youngs_modulus=1e8, poisson_ratio=0.3)
    b.body("bar", mesh=fdem.Mesh.rectangle(0.0, 0.0, 1.0, 0.1, 20, 2), material=m,
           velocity_gradient=[[0.5, 0.0], [0.2, 0.0]], origin=[0.0, 0.0])
    b.boundary("bar", "left", fix=["x", "y"])
    b.boundary("bar", "right", velocity=(0.0, 0.0))
    sim = b.build()
    sim.supports["bar/right"].velocity = (0.5, 0.2)
    rec = fdem.EnergyRecorder()
    sim.run(callback=rec, every=1)
    h = rec.arrays()
    scale = (h["kinetic"] + h["strain"]).max()
    assert np.abs(h["total"] - h["total"][0]).max() < 1e-5 * scale
