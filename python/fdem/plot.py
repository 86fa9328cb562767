"""Pictures from Python (matplotlib): a field on the deformed mesh, and energy histories.

    import fdem.plot
    fig, ax = fdem.plot.tripcolor(sim, field="von_mises")
    fig.savefig("stress.png", dpi=150)
    fdem.plot.energy_history(recorder_or_history_csv).figure.savefig("energy.png")

Uses whatever matplotlib backend is active (set MPLBACKEND=Agg on a machine without a display).
"""
import numpy as np

_FIELDS = {
    "von_mises": ("von Mises stress", "Pa"),
    "sxx": ("stress xx", "Pa"),
    "syy": ("stress yy", "Pa"),
    "sxy": ("stress xy", "Pa"),
    "pressure": ("pressure -(sxx + syy)/2", "Pa"),
    "speed": ("speed |v| (node average)", "m/s"),
    "body": ("body id", "-"),
}


def field_values(sim, field):
    """Per-triangle values of a named field (see FIELDS) or a given (n_tris,) array."""
    if not isinstance(field, str):
        vals = np.asarray(field, dtype=float)
        if vals.shape != (sim.model.num_tris,):
            raise ValueError(f"field array must have shape ({sim.model.num_tris},), "
                             f"got {vals.shape}")
        return vals
    if field == "von_mises":
        return sim.von_mises()
    if field in ("sxx", "syy", "sxy", "pressure"):
        s = sim.stress()
        return {"sxx": s[:, 0, 0], "syy": s[:, 1, 1], "sxy": s[:, 0, 1],
                "pressure": -0.5 * (s[:, 0, 0] + s[:, 1, 1])}[field]
    if field == "speed":
        speed = np.linalg.norm(sim.state.v, axis=1)
        return speed[sim.model.tri_nodes].mean(axis=1)
    if field == "body":
        return sim.model.tri_body.astype(float)
    raise ValueError(f"unknown field {field!r}; expected one of {sorted(_FIELDS)} "
                     "or an array with one value per triangle")


FIELDS = sorted(_FIELDS)


def tripcolor(sim, field="von_mises", ax=None, cmap="viridis", deformed=True, colorbar=True,
              title=None, **kwargs):
    """Colour every triangle of the (deformed) mesh by a per-triangle field.

    field: "von_mises", "sxx", "syy", "sxy", "pressure" [Pa], "speed" [m/s], "body", or an
    (n_tris,) array. deformed=False draws the reference configuration. Extra keyword arguments
    go to matplotlib's tripcolor. Returns (figure, axes).
    """
    import matplotlib.pyplot as plt
    from matplotlib.tri import Triangulation

    if ax is None:
        fig, ax = plt.subplots(figsize=(8, 4))
    else:
        fig = ax.figure
    x = sim.state.x if deformed else sim.model.node_x0
    tri = Triangulation(x[:, 0], x[:, 1], sim.model.tri_nodes)
    vals = field_values(sim, field)
    pc = ax.tripcolor(tri, facecolors=vals, cmap=cmap, **kwargs)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    if isinstance(field, str):
        label, unit = _FIELDS[field]
        if colorbar:
            fig.colorbar(pc, ax=ax, label=f"{label} [{unit}]", shrink=0.8)
    elif colorbar:
        fig.colorbar(pc, ax=ax, shrink=0.8)
    ax.set_title(title if title is not None else f"{sim.name}: t = {sim.time:.4g} s")
    return fig, ax


def energy_history(history, ax=None, title="energy balance"):
    """Plot the energies of a run against time.

    history: an fdem.EnergyRecorder, a dict of arrays (time, kinetic, strain, contact, ...,
    total), or the path of a history.csv. Returns the axes.
    """
    import matplotlib.pyplot as plt

    from .history import EnergyRecorder, read_history

    if isinstance(history, EnergyRecorder):
        h = history.arrays()
    elif isinstance(history, str):
        h = read_history(history)
    else:
        h = history
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 4))
    t = h["time"]
    for key, label in [("kinetic", "kinetic"), ("strain", "strain"), ("contact", "contact"),
                       ("work_gravity", "work of gravity"), ("work_external", "external work"),
                       ("dissipated_viscous", "viscous dissipation"),
                       ("dissipated_contact", "contact dissipation"),
                       # fracture (theory eqs. 9.18, 9.19): sim.energy's keys, history.csv's names
                       ("joint", "joint energy"), ("energy.joint", "joint energy"),
                       ("fracture", "fracture work"), ("energy.fracture", "fracture work"),
                       ("total", "total (balance)")]:
        if key in h and np.any(np.asarray(h[key]) != 0):
            ax.plot(t, h[key], label=label, lw=2.0 if key == "total" else 1.2)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("energy per unit thickness [J/m]")
    ax.set_title(title)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return ax
