"""Y1: zero-copy views that follow the state (spec parallel-and-python.md §6.3)."""
import gc

import numpy as np
import pytest

import fdem
from conftest import example


@pytest.fixture
def sim():
    return fdem.Simulation.from_toml(example("03_contact_slide"))


def test_views_are_zero_copy_and_follow_the_state(sim):
    x = sim.state.x
    x_before = x.copy()
    addr = x.__array_interface__["data"][0]
    sim.step(5)
    x2 = sim.state.x
    assert np.shares_memory(x, x2)
    assert x2.__array_interface__["data"][0] == addr  # the same C++ storage, no copy
    assert not np.array_equal(x, x_before)  # the old view shows the new positions
    assert x.shape == (sim.model.num_nodes, 2) and x.dtype == np.float64


def test_read_only_and_writable_views(sim):
    assert not sim.state.x.flags.writeable
    assert not sim.state.f.flags.writeable
    assert not sim.state.f_contact.flags.writeable
    assert not sim.model.tri_nodes.flags.writeable
    assert not sim.model.node_x0.flags.writeable
    assert sim.state.v.flags.writeable
    with pytest.raises(ValueError):
        sim.state.x[0, 0] = 1.0
    with pytest.raises(ValueError):
        sim.model.tri_nodes[0, 0] = 3


def test_model_views_match_the_model(sim):
    m = sim.model
    tn = m.tri_nodes
    assert tn.shape == (m.num_tris, 3) and tn.dtype == np.int32
    assert tn.min() >= 0 and tn.max() < m.num_nodes
    # counter-clockwise reference triangles: positive area, equal to tri_area0
    X = m.node_x0
    a, b, c = X[tn[:, 0]], X[tn[:, 1]], X[tn[:, 2]]
    area = 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    np.testing.assert_allclose(area, m.tri_area0, rtol=1e-12)
    assert m.node_mass.shape == (m.num_nodes,)
    assert np.all(m.node_mass > 0)
    assert m.body_names == ["slab", "block"]


def test_view_keeps_the_simulation_alive():
    s = fdem.Simulation.from_toml(example("03_contact_slide"))
    s.step(3)
    x = s.state.x
    expected = x.copy()
    del s
    gc.collect()
    np.testing.assert_array_equal(x, expected)  # memory still owned: no use after free


def test_writing_velocities_changes_the_motion(sim):
    block = np.flatnonzero(sim.model.node_body == 1)
    sim.state.v[block] = (0.0, 0.0)  # stop the thrown block through the writable view
    sim.step(1)
    assert np.all(np.abs(sim.state.v[block, 0]) < 1e-3)
    sim.set_velocities(np.zeros((sim.model.num_nodes, 2)))
    assert np.all(sim.state.v == 0)
    with pytest.raises(ValueError, match="shape"):
        sim.set_velocities(np.zeros((3, 2)))


def test_set_positions_copies_and_rebuilds(sim):
    x = np.array(sim.state.x)
    x[:, 0] += 1e-3
    sim.set_positions(x)
    np.testing.assert_array_equal(sim.state.x, x)
    sim.step(2)  # runs with the moved mesh (rigid shift: no strain)
    with pytest.raises(ValueError, match="not finite"):
        x[0, 0] = np.nan
        sim.set_positions(x)


def test_energy_and_derived_fields(sim):
    sim.step(10)
    e = sim.energy
    assert set(e) >= {"kinetic", "strain", "contact", "work_gravity", "work_external",
                      "dissipated_viscous", "dissipated_contact", "total", "time"}
    assert e["total"] == pytest.approx(e["kinetic"] + e["strain"] + e["contact"]
                                       - e["work_gravity"] - e["work_external"]
                                       + e["dissipated_viscous"] + e["dissipated_contact"])
    s = sim.stress()
    assert s.shape == (sim.model.num_tris, 2, 2)
    np.testing.assert_allclose(s[:, 0, 1], s[:, 1, 0])  # Cauchy stress is symmetric
    vm = sim.von_mises()
    sxx, syy, sxy = s[:, 0, 0], s[:, 1, 1], s[:, 0, 1]
    np.testing.assert_allclose(vm, np.sqrt(sxx**2 - sxx * syy + syy**2 + 3 * sxy**2), rtol=1e-12)
    r = sim.resultants()
    assert set(r) == {"slab", "block", "slab/slab_base"}
    # the base support's reaction is the sum of its nodes' reactions (theory eq. 8.1)
    np.testing.assert_allclose(r["slab/slab_base"]["reaction"], sim.state.bc_reaction.sum(axis=0),
                               rtol=1e-12)
    assert r["slab"]["reaction"] == r["slab/slab_base"]["reaction"]
    # the mean displacement of the block is the mass-weighted mean of x - X over its nodes
    blk = sim.model.node_body == 1
    m = sim.model.node_mass[blk]
    u = (m[:, None] * (sim.state.x[blk] - sim.model.node_x0[blk])).sum(axis=0) / m.sum()
    np.testing.assert_allclose(r["block"]["u"], u, rtol=1e-12)
    assert r["block"]["u"][0] > 0  # thrown to the right
