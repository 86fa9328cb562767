"""Y4: a model built in Python equals the TOML scenario bit for bit."""
import numpy as np
import pytest

import fdem
from conftest import ROOT, cli_hash, example


def example03_builder(mesh_from_memory):
    d = ROOT / "examples" / "03_contact_slide"
    b = fdem.ModelBuilder(name="example03-builder", base_dir=str(d))
    b.simulation(end_time=1.1, dt="auto", dt_fraction=0.2, gravity=(0.0, -9.81))
    b.output(interval=0.02, dir="out/03_contact_slide")
    rubber = b.material("rubber", density=1000.0, youngs_modulus=5.0e7, poisson_ratio=0.0,
                        damping_ratio=0.05)
    if mesh_from_memory:
        mesh = fdem.Mesh.read(str(d / "slide.geo"), mesh_size=0.05)
        b.body("slab", mesh=mesh, group="slab", material=rubber)
        b.body("block", mesh=mesh, group="block", material=rubber, velocity=(3.0, -0.5))
    else:
        b.body("slab", mesh="slide.geo", mesh_size=0.05, group="slab", material=rubber)
        b.body("block", mesh="slide.geo", mesh_size=0.05, group="block", material=rubber,
               velocity=(3.0, -0.5))
    b.boundary("slab", "slab_base", fix=["x", "y"])
    b.contact("smooth", penalty=2.5e8, friction=0.3, damping=1.2e4, damp_normal_only=True)
    return b


@pytest.mark.parametrize("mesh_from_memory", [False, True])
def test_builder_equals_toml(mesh_from_memory, tmp_path):
    sim = example03_builder(mesh_from_memory).build()
    ref = fdem.Simulation.from_toml(example("03_contact_slide"))
    assert sim.dt == ref.dt
    np.testing.assert_array_equal(sim.model.node_x0, ref.model.node_x0)
    np.testing.assert_array_equal(sim.model.tri_nodes, ref.model.tri_nodes)
    end = 300 * sim.dt
    sim.end_time = end
    sim.run()
    assert sim.state_hash() == cli_hash(example("03_contact_slide"), end, tmp_path)


def rectangle_arrays():
    r = fdem.Mesh.rectangle(0.0, 0.0, 1.0, 0.2, 10, 2)
    X, T = r.nodes, r.triangles
    bottom = np.flatnonzero(np.isclose(X[:, 1], 0.0))
    return X, T, bottom


def bar_builder(mesh):
    b = fdem.ModelBuilder()
    b.simulation(end_time=1e-3, dt="auto", gravity=(0.0, -9.81))
    steel = b.material("steel", density=7800, youngs_modulus=200e9, poisson_ratio=0.3)
    b.body("bar", mesh=mesh, material=steel)
    b.boundary("bar", "left", fix=["x", "y"])
    return b


def test_mesh_from_numpy_arrays_equals_generated_mesh():
    r = fdem.Mesh.rectangle(0.0, 0.0, 1.0, 0.2, 10, 2)
    X, T = r.nodes, r.triangles
    left = np.flatnonzero(np.isclose(X[:, 0], 0.0))
    left_edges = np.stack([left[:-1], left[1:]], axis=1)
    m = fdem.Mesh(X, T, groups={"left": left_edges}, triangle_groups={"domain": np.arange(len(T))})
    assert m.groups == {"left": "curve", "domain": "surface"}
    a, b = bar_builder(r).build(), bar_builder(m).build()
    a.run(steps=200)
    b.run(steps=200)
    assert a.state_hash() == b.state_hash()
    # the bar bends under gravity, held at its left end
    assert b.state.x[:, 1].min() < 0


def test_mesh_array_errors():
    X, T, _ = rectangle_arrays()
    with pytest.raises(fdem.InputError, match=r"nodes: expected an array of shape \(n, 2\)"):
        fdem.Mesh(X[:, :1], T)
    bad = T.copy()
    bad[3, 1] = len(X) + 7
    with pytest.raises(fdem.InputError, match=rf"triangles: row 3 refers to node {len(X) + 7}"):
        fdem.Mesh(X, bad)
    with pytest.raises(fdem.InputError, match="group 'g'"):
        fdem.Mesh(X, T, groups={"g": np.zeros((2, 3), dtype=int)})


def test_builder_errors_name_the_generated_line():
    b = bar_builder(fdem.Mesh.rectangle(0.0, 0.0, 1.0, 0.2, 10, 2))
    b.material("bad", density=-1.0, youngs_modulus=1e9, poisson_ratio=0.2)
    text = b.to_toml()
    line = text.splitlines().index("density = -1.0") + 1
    with pytest.raises(fdem.InputError) as e:
        b.build()
    assert e.value.line == line and e.value.key.endswith("density")
    assert "<ModelBuilder>:%d:" % line in str(e.value)
