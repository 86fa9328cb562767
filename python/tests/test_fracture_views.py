"""Fracture from Python (docs/python.md): the joints, their history, the fragments and the joint
energies of a running model, checked against the CSV files the same run writes (cracks.csv,
history.csv) and against their definitions (theory §9)."""
import csv

import numpy as np
import pytest

import fdem
from conftest import example


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """Example 11 (a jointed disc hitting a plate) to 6e-5 s, written to a temporary folder."""
    out = tmp_path_factory.mktemp("impact")
    sim = fdem.Simulation.from_toml(example("11_impact_fragmentation"))
    sim.open_output(str(out))
    first = sim.state.joint_status  # a view taken before any step
    sim.end_time = 6e-5  # (the final step writes a history row)
    sim.run()
    return sim, out, first


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_model_joints(run):
    sim, _, _ = run
    m = sim.model
    jn = m.joint_nodes
    assert jn.dtype == np.int32 and jn.ndim == 2 and jn.shape[1] == 4 and len(jn) > 1000
    assert jn.min() >= 0 and jn.max() < m.num_nodes
    assert not jn.flags.writeable
    # h_0 = |x0[node 1] - x0[node 0]| (theory eq. 9.1); nodes 0 and 3, 1 and 2 coincide
    X = m.node_x0
    np.testing.assert_allclose(m.joint_length0, np.linalg.norm(X[jn[:, 1]] - X[jn[:, 0]], axis=1),
                               rtol=1e-12)
    np.testing.assert_array_equal(X[jn[:, 0]], X[jn[:, 3]])
    np.testing.assert_array_equal(X[jn[:, 1]], X[jn[:, 2]])


def test_joint_history_is_that_of_cracks_csv(run):
    sim, out, first = run
    st = sim.state
    status = st.joint_status
    assert np.shares_memory(first, status)  # zero-copy views that follow the state
    assert not status.flags.writeable and not st.joint_work.flags.writeable
    broken = np.flatnonzero(status == 2)
    assert len(broken) > 10 and np.any(status == 1) and np.any(status == 0)
    cracks = rows(out / "cracks.csv")
    assert sorted(int(r["joint"]) for r in cracks) == broken.tolist()
    for r in cracks:
        j = int(r["joint"])
        assert st.joint_break_step[j] == int(r["step"])
        assert st.joint_mode[j] == int(r["mode"])
        assert st.joint_work[j] == float(r["work"])
    intact = status != 2
    assert np.all(st.joint_break_step[intact] == -1) and np.all(st.joint_mode[intact] == 0)
    # a broken joint has at least failure_points (2) points at D_max >= 1 (theory eq. 9.15)
    assert st.joint_damage.shape == (len(status), 3)
    assert np.all((st.joint_damage[broken] >= 1).sum(axis=1) >= 2)
    assert np.all(st.joint_damage[status == 0] == 0)


def test_fragments_and_energies_are_those_of_history_csv(run):
    sim, out, _ = run
    frag = sim.state.tri_fragment
    assert frag.shape == (sim.model.num_tris,) and frag.dtype == np.int32
    # a fragment's id is its smallest triangle
    assert np.all(frag <= np.arange(len(frag))) and np.all(frag[frag] == frag)
    last = rows(out / "history.csv")[-1]
    assert float(last["time"]) == sim.time
    assert len(np.unique(frag)) == int(last["fragments"])
    assert int(last["joints.broken"]) == int((sim.state.joint_status == 2).sum())
    e = sim.energy
    assert e["joint"] > 0 and e["fracture"] > 0
    assert e["joint"] == float(last["energy.joint"])
    assert e["fracture"] == float(last["energy.fracture"])
    assert e["total"] == float(last["total"])
