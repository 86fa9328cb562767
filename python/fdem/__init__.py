"""fdem: 2-D combined finite-discrete element simulator with the smooth contact of
Lei, Rougier, Euser & Munjiza (2020).

Run a scenario file::

    import fdem
    sim = fdem.Simulation.from_toml("examples/03_contact_slide/scenario.toml")
    sim.run(until=0.1)                 # the GIL is released while C++ steps
    print(sim.energy["total"], sim.state.x.shape)

Build one in Python (fdem.ModelBuilder), look at the state through zero-copy NumPy views
(``sim.state.x``, ``sim.state.v``, ``sim.model.tri_nodes``), change support velocities between
steps (``sim.set_support_velocity``), save and restore checkpoints, plot with ``fdem.plot``.
Errors raise ``fdem.InputError`` (bad input, a ValueError) and ``fdem.SimulationError`` (the
physics failed, a RuntimeError) with the same messages as the ``fdem`` command line.
Units are SI throughout. Full reference: docs/python.md.
"""
from ._fdem import (  # noqa: F401
    InputError,
    Mesh,
    Model,
    Simulation,
    SimulationError,
    State,
    Support,
    __version__,
)
from .builder import ModelBuilder  # noqa: F401
from . import history  # noqa: F401
from .history import EnergyRecorder  # noqa: F401

__all__ = [
    "Simulation",
    "Model",
    "State",
    "Mesh",
    "Support",
    "ModelBuilder",
    "EnergyRecorder",
    "InputError",
    "SimulationError",
    "plot",
    "__version__",
]


def __getattr__(name):
    # fdem.plot imports matplotlib: only when asked for
    if name == "plot":
        from . import plot

        return plot
    raise AttributeError(f"module 'fdem' has no attribute {name!r}")
